#!/usr/bin/env python3
"""The material test scene: the Cornell box (../cornell-box, its walls and
light unchanged, its two blocks removed) with a glossy floor, a smooth glass
sphere and a rough copper block, written as OBJ + MTL in the classic fields a
user's exporter writes (Kappa maps them as Blender's importer does:
docs/scene-format.md).

    python3 assets/material-box/gen.py    # writes material_box.obj, .mtl
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from icosphere import icosphere  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
BOX = os.path.join(HERE, "..", "cornell-box", "cornell_box.obj")

MTL = """# Written by gen.py: the Cornell box's materials, a glossy floor, glass and rough copper.
newmtl white
Ka 0 0 0
Kd 0.725 0.71 0.68
Ks 0 0 0

newmtl red
Ka 0 0 0
Kd 0.63 0.065 0.05
Ks 0 0 0

newmtl green
Ka 0 0 0
Kd 0.14 0.45 0.091
Ks 0 0 0

newmtl light
Ka 0 0 0
Kd 0 0 0
Ks 0 0 0
Ke 17 12 4

# illum 2 with Ks 0.5: the IOR's own reflectance (F0 0.04) over the white;
# Ns 700: roughness 1 - sqrt(0.7) = 0.163.
newmtl glossy_floor
Ka 0 0 0
Kd 0.725 0.71 0.68
Ks 0.5 0.5 0.5
Ns 700
illum 2

# illum 7 (refraction, Fresnel on): glass of IOR 1.5; Ns 1000: smooth.
newmtl glass
Ka 0 0 0
Kd 0 0 0
Ks 1 1 1
Ns 1000
Ni 1.5
Tf 1 1 1
illum 7

# illum 3 with Ka 1: metallic (Blender's mapping); Ns 400: roughness 0.368.
newmtl rough_copper
Ka 1 1 1
Kd 0.955 0.638 0.538
Ks 1 1 1
Ns 400
illum 3
"""


def box(center, size, angle_deg):
    """An axis box rotated about y: 8 corners and 12 outward triangles."""
    cx, cy, cz = center
    sx, sy, sz = size
    a = math.radians(angle_deg)
    ca, sa = math.cos(a), math.sin(a)
    corners = []
    for y in (0, sy):
        for (x, z) in ((-sx / 2, -sz / 2), (sx / 2, -sz / 2), (sx / 2, sz / 2), (-sx / 2, sz / 2)):
            corners.append((cx + ca * x + sa * z, cy + y, cz - sa * x + ca * z))
    faces = [(0, 1, 2), (0, 2, 3),  # bottom (outward -y)
             (4, 6, 5), (4, 7, 6),  # top
             (0, 4, 5), (0, 5, 1), (1, 5, 6), (1, 6, 2), (2, 6, 7), (2, 7, 3), (3, 7, 4), (3, 4, 0)]
    return corners, faces


def main():
    out = ["# The material test scene, written by gen.py (the Cornell box's walls and light,",
           "# a glossy floor, a smooth glass sphere with vertex normals, a rough copper block).",
           "mtllib material_box.mtl", ""]
    with open(BOX) as f:
        lines = f.read().splitlines()
    vertices, objects, current = [], [], None
    for line in lines:
        if line.startswith("o "):
            current = {"name": line[2:].strip(), "mtl": None, "faces": []}
            objects.append(current)
        elif line.startswith("v "):
            vertices.append(line)
            current.setdefault("verts", []).append(len(vertices))
        elif line.startswith("usemtl "):
            current["mtl"] = line.split()[1]
        elif line.startswith("f "):
            current["faces"].append([int(i) for i in line.split()[1:]])
    n = 0
    for o in objects:
        if "block" in o["name"]:
            continue
        out.append("o " + o["name"])
        out.append("usemtl " + ("glossy_floor" if o["name"] == "floor" else o["mtl"]))
        remap = {}
        for old in sorted({i for f in o["faces"] for i in f}):
            n += 1
            remap[old] = n
            out.append(vertices[old - 1])
        for f in o["faces"]:
            out.append("f " + " ".join(str(remap[i]) for i in f))
        out.append("")
    # The glass sphere, smooth-shaded: its vertex normals are its positions' directions.
    v, f = icosphere(3)
    centre, radius = (370.0, 100.0, 300.0), 100.0
    out += ["o glass_sphere", "usemtl glass"]
    for p in v:
        out.append("v %.6f %.6f %.6f" % tuple(centre[i] + radius * p[i] for i in range(3)))
    for p in v:
        out.append("vn %.6f %.6f %.6f" % p)
    nn = 0
    for a, b, c in f:
        out.append("f %d//%d %d//%d %d//%d" % (n + a + 1, nn + a + 1, n + b + 1, nn + b + 1, n + c + 1, nn + c + 1))
    n += len(v)
    out.append("")
    corners, faces = box((180.0, 0.0, 330.0), (150.0, 260.0, 150.0), 20.0)
    out += ["o copper_block", "usemtl rough_copper"]
    for p in corners:
        out.append("v %.6f %.6f %.6f" % p)
    for a, b, c in faces:
        out.append("f %d %d %d" % (n + a + 1, n + b + 1, n + c + 1))
    n += len(corners)
    with open(os.path.join(HERE, "material_box.obj"), "w") as fo:
        fo.write("\n".join(out) + "\n")
    with open(os.path.join(HERE, "material_box.mtl"), "w") as fo:
        fo.write(MTL)


if __name__ == "__main__":
    main()
