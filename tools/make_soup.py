#!/usr/bin/python3
"""Writes a random triangle soup as OBJ, for scale tests:

    tools/make_soup.py N OUT.obj [--seed S] [--fixed-edge E]

N triangles with centres uniform in [-1, 1]^3. By default each triangle's
vertices lie within 2/sqrt(N) of its centre on every axis, so the soup's
total area stays constant as N grows (the paper's case of O(N^(1/3)) cells
per ray and O(N) storage); --fixed-edge E keeps that spread at E instead.
Written in chunks, so 10^7 triangles take about a minute and little memory.
"""
import argparse
import os
import sys

import numpy as np


# Three vertices, then the face made of them (relative indices).
TRIANGLE = "v %.7g %.7g %.7g\nv %.7g %.7g %.7g\nv %.7g %.7g %.7g\nf -3 -2 -1\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("n", type=int)
    p.add_argument("out")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--fixed-edge", type=float, default=0.0)
    a = p.parse_args()
    if a.n < 1:
        sys.exit("make_soup.py: N must be at least 1")
    rng = np.random.default_rng(a.seed)
    edge = a.fixed_edge if a.fixed_edge > 0 else 2.0 / np.sqrt(a.n)
    chunk = 250_000
    tmp = a.out + ".part"
    with open(tmp, "w") as f:
        f.write(f"# {a.n} random triangles, seed {a.seed}, edge spread {edge:g} (tools/make_soup.py)\n")
        for start in range(0, a.n, chunk):
            m = min(chunk, a.n - start)
            centres = rng.uniform(-1, 1, size=(m, 1, 3))
            tris = (centres + edge * rng.uniform(-1, 1, size=(m, 3, 3))).reshape(m, 9).tolist()
            f.write("".join(TRIANGLE % tuple(t) for t in tris))
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
