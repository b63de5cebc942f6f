#!/usr/bin/python3
"""Writes one scene of the scaling study (the paper's Table 2) as OBJ + scene.json:

    tools/make_scaling_scene.py FAMILY N DIR [--fixed-edge E]

FAMILY is one of
  sphere         a tessellated unit sphere (tools/make_sphere.py): a fixed smooth surface cut finer,
                 the paper's section 9.1 (e_D = 1/2, e_SA = 0, e_V = 0)
  soup           N random triangles in [-1, 1]^3 whose edge shrinks as N^(-1/2) (tools/make_soup.py):
                 constant total area, the same exponents as the sphere but no surface to stop at
  soup-fixed     the same soup with a fixed edge spread E (default 0.2, the soup's at N = 100): total
                 diameter and area grow as N (e_D = 1, e_SA = 1)
  sphere-in-box  a sphere of radius 0.05 of N - 10 triangles in an open box of 10 triangles and side 20:
                 a small dense object in a large empty grid, where kappa is expected to grow with N

Every scene has a white sky (environment 1) so that paths bounce, a camera that sees the object and a
128 x 128 film. DIR/scene.json is written last, so a scene whose JSON exists is complete.
"""
import argparse
import json
import os
import subprocess
import sys

TOOLS = os.path.dirname(os.path.abspath(__file__))
FAMILIES = ("sphere", "soup", "soup-fixed", "sphere-in-box")

# Floor and four walls of [-10, 10] x [0, 20] x [-10, 10], open at the top so the sky lights the inside.
BOX_OBJ = """# open box of side 20, 10 triangles (tools/make_scaling_scene.py)
v -10 0 -10
v 10 0 -10
v 10 0 10
v -10 0 10
v -10 20 -10
v 10 20 -10
v 10 20 10
v -10 20 10
f 1 3 2
f 1 4 3
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""


def run(*args):
    subprocess.run([sys.executable, *args], check=True)


def write_atomic(path, text):
    tmp = path + ".part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("family", choices=FAMILIES)
    p.add_argument("n", type=int)
    p.add_argument("dir")
    p.add_argument("--fixed-edge", type=float, default=0.2)
    a = p.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    n = a.n
    if a.family == "sphere":
        run(os.path.join(TOOLS, "make_sphere.py"), str(n), os.path.join(a.dir, "mesh.obj"))
        meshes = ["mesh.obj"]
        camera = {"eye": [0.8, 0.9, 3.4], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40}
    elif a.family in ("soup", "soup-fixed"):
        extra = ["--fixed-edge", str(a.fixed_edge)] if a.family == "soup-fixed" else []
        run(os.path.join(TOOLS, "make_soup.py"), str(n), os.path.join(a.dir, "mesh.obj"), *extra)
        meshes = ["mesh.obj"]
        camera = {"eye": [1.2, 1.5, 4.5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40}
    else:
        if n < 22:
            sys.exit("make_scaling_scene.py: sphere-in-box needs N of at least 22")
        run(os.path.join(TOOLS, "make_sphere.py"), str(n - 10), os.path.join(a.dir, "mesh.obj"),
            "--radius", "0.05", "--centre", "0", "1", "0")
        write_atomic(os.path.join(a.dir, "box.obj"), BOX_OBJ)
        meshes = ["mesh.obj", "box.obj"]
        # Close to the sphere, which fills about half the frame; the rest of the view is the far walls.
        camera = {"eye": [0.08, 1.08, 0.3], "look_at": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 30}
    scene = {"meshes": meshes, "camera": camera, "environment": [1, 1, 1], "film": {"width": 128, "height": 128}}
    write_atomic(os.path.join(a.dir, "scene.json"), json.dumps(scene, indent=1) + "\n")


if __name__ == "__main__":
    main()
