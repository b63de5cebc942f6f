#!/usr/bin/python3
"""Writes a tessellated sphere as OBJ, for scale tests:

    tools/make_sphere.py N OUT.obj [--radius R] [--centre X Y Z]

A cube sphere: each face of a cube cut into m x m quads, two triangles each,
projected onto the sphere through the equal-angle map (tan), so that the
12 m^2 triangles have nearly equal areas (a UV sphere's slivers at the poles
would make the soup of sizes this family is meant to avoid). m is chosen so
that 12 m^2 is closest to N; the OBJ's first line gives the count written.
Every vertex is computed from its integer position on the cube's surface, so
the copies that neighbouring faces write of an edge's vertices are the same
floats: the surface is closed, no ray slips through a seam.
"""
import argparse
import os
import sys

import numpy as np


def face_vertices(m, axis, sign):
    """(m+1)^2 integer points of one cube face, coordinates in [-m, m] step 2."""
    u, v = np.meshgrid(np.arange(-m, m + 1, 2), np.arange(-m, m + 1, 2), indexing="ij")
    pts = np.empty(u.shape + (3,), dtype=np.int64)
    other = [a for a in range(3) if a != axis]
    pts[..., axis] = sign * m
    # Swap the in-plane axes on the negative faces so every face winds outwards.
    a, b = (other[0], other[1]) if sign > 0 else (other[1], other[0])
    if axis == 1:
        a, b = b, a
    pts[..., a] = u
    pts[..., b] = v
    return pts.reshape(-1, 3)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("n", type=int)
    p.add_argument("out")
    p.add_argument("--radius", type=float, default=1.0)
    p.add_argument("--centre", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    a = p.parse_args()
    if a.n < 12:
        sys.exit("make_sphere.py: N must be at least 12")
    m = max(1, int(round(np.sqrt(a.n / 12.0))))
    centre = np.array(a.centre)
    lines = []
    faces = []
    base = 0
    for axis in range(3):
        for sign in (1, -1):
            ip = face_vertices(m, axis, sign)
            # Equal-angle map of the cube [-1, 1]^3 onto the sphere.
            q = np.tan(ip / m * (np.pi / 4))
            q /= np.linalg.norm(q, axis=1, keepdims=True)
            lines.append(q * a.radius + centre)
            # Quad (i, j) of the (m+1) x (m+1) lattice, 1-based OBJ indices.
            i, j = np.meshgrid(np.arange(m), np.arange(m), indexing="ij")
            v00 = base + i * (m + 1) + j + 1
            v10, v01, v11 = v00 + (m + 1), v00 + 1, v00 + m + 2
            faces.append(np.stack([v00, v10, v11], -1).reshape(-1, 3))
            faces.append(np.stack([v00, v11, v01], -1).reshape(-1, 3))
            base += (m + 1) ** 2
    verts = np.concatenate(lines)
    tris = np.concatenate(faces)
    tmp = a.out + ".part"
    with open(tmp, "w") as f:
        f.write("# cube sphere, %d triangles, radius %g, centre %g %g %g (tools/make_sphere.py)\n"
                % (len(tris), a.radius, *centre))
        f.write("".join("v %.9g %.9g %.9g\n" % tuple(v) for v in verts.tolist()))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in tris.tolist()))
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
