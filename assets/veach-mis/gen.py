#!/usr/bin/env python3
"""Veach's multiple importance sampling scene (Veach 1997, fig. 9.2): four
metal plates of increasing roughness, each tilted to reflect a row of four
spherical lights of increasing size and equal power towards the camera. Light
sampling wins on the rough plates and the small lights, BSDF sampling on the
smooth plates and the large lights; MIS must be good everywhere. Geometry
after the layout of Veach's figure, computed here (no file is copied); a
grey back wall and floor catch some light.

    python3 assets/veach-mis/gen.py    # writes veach_mis.obj, veach_mis.mtl
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from icosphere import icosphere  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

CAMERA = (0.0, 2.0, 15.0)
LIGHT_ROW = [(-3.75, 0.03), (-1.25, 0.1), (1.25, 0.3), (3.75, 0.9)]  # (x, radius), small to large
LIGHT_Y, LIGHT_Z = 4.0, -1.5
# Plate centres (y, z) down a slope towards the camera, and their GGX
# roughness (Pr; alpha = Pr^2 = 0.005, 0.02, 0.05, 0.1 as Mitsuba's scene).
PLATES = [((-0.3, 0.5), 0.0707), ((-0.95, 2.0), 0.1414), ((-1.5, 3.5), 0.2236), ((-1.95, 5.0), 0.3162)]
PLATE_W, PLATE_D = 8.0, 1.2


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def sub(a, b):
    return tuple(a[i] - b[i] for i in range(3))


def add(a, b):
    return tuple(a[i] + b[i] for i in range(3))


def scale(a, s):
    return tuple(c * s for c in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def main():
    obj = ["# Veach's MIS scene, written by gen.py.", "mtllib veach_mis.mtl", ""]
    mtl = ["# Written by gen.py. Plates: metal (Pm 1) of GGX roughness Pr; lights of equal power.", ""]
    n = 0

    def quad(name, material, corners):
        nonlocal n
        obj.extend(["o " + name, "usemtl " + material])
        obj.extend("v %.6f %.6f %.6f" % c for c in corners)
        obj.append("f %d %d %d" % (n + 1, n + 2, n + 3))
        obj.append("f %d %d %d" % (n + 1, n + 3, n + 4))
        obj.append("")
        n += 4

    target = (0.0, LIGHT_Y, LIGHT_Z)
    for i, ((y, z), rough) in enumerate(PLATES):
        c = (0.0, y, z)
        normal = normalize(add(normalize(sub(CAMERA, c)), normalize(sub(target, c))))
        along = normalize(cross((1.0, 0.0, 0.0), normal))  # in the plate, across x
        hx, hd = (PLATE_W / 2, 0, 0), scale(along, PLATE_D / 2)
        corners = [sub(sub(c, hx), hd), add(sub(c, hd), hx), add(add(c, hx), hd), add(sub(c, hx), hd)]
        # Counter-clockwise seen from the normal's side.
        if sum(cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]))[k] * normal[k] for k in range(3)) < 0:
            corners.reverse()
        quad("plate%d" % (i + 1), "plate%d" % (i + 1), corners)
        mtl += ["newmtl plate%d" % (i + 1), "Kd 0.5 0.5 0.5", "Pm 1", "Pr %g" % rough, ""]

    v, f = icosphere(2)
    power = 1.0  # radiance * radius^2, the same for every light
    for i, (x, r) in enumerate(LIGHT_ROW):
        obj.extend(["o light%d" % (i + 1), "usemtl light%d" % (i + 1)])
        obj.extend("v %.6f %.6f %.6f" % (x + r * p[0], LIGHT_Y + r * p[1], LIGHT_Z + r * p[2]) for p in v)
        obj.extend("f %d %d %d" % (n + a + 1, n + b + 1, n + c + 1) for a, b, c in f)
        obj.append("")
        n += len(v)
        L = power / (r * r) * 0.8
        mtl += ["newmtl light%d" % (i + 1), "Kd 0 0 0", "Ke %g %g %g" % (L, L, L), ""]

    quad("floor", "grey", [(-12, -3, -6), (-12, -3, 16), (12, -3, 16), (12, -3, -6)])
    quad("back_wall", "grey", [(-12, -3, -6), (12, -3, -6), (12, 10, -6), (-12, 10, -6)])
    mtl += ["newmtl grey", "Kd 0.2 0.2 0.2", ""]
    with open(os.path.join(HERE, "veach_mis.obj"), "w") as fo:
        fo.write("\n".join(obj) + "\n")
    with open(os.path.join(HERE, "veach_mis.mtl"), "w") as fo:
        fo.write("\n".join(mtl))


if __name__ == "__main__":
    main()
