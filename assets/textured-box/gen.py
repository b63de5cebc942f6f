#!/usr/bin/env python3
"""The texture test scene: a small open-fronted box (2 x 2 x 2, y up) whose
floor and back wall carry colour maps, a cut-out card with a checkerboard
opacity map in the middle, a metal panel whose roughness is a map, and a
square light under the ceiling. OBJ + MTL as a user's exporter writes them;
Kappa reads the maps as Blender 3.4's importer does (map_Kd sRGB, map_d the
alpha channel, map_Pr linear, `-s` scales the texture coordinates).

    python3 assets/textured-box/gen.py    # writes textured_box.obj, .mtl,
                                          # scene.json and four 64 x 64 PNGs

Objects (every face has vt; quads written as two counter-clockwise triangles
seen from the side the normal points to):
  floor        y = 0, x, z in [-1, 1], normal +y; vt (0,0) at (-1, 0, 1), u along +x,
               v along -z. floor_checker.png: 8 x 8 checks of 8 px, cream and blue.
  back_wall    z = -1, x in [-1, 1], y in [0, 2], normal +z; u along +x, v along +y.
               wall_stripes.png holds 2 periods of vertical stripes (4 stripes of 16 px)
               and the MTL says `-s 2 1 1`: 4 periods, 8 stripes of 0.25 m on the wall.
  left_wall    x = -1, normal +x, plain red;   right_wall  x = +1, normal -x, plain green.
  ceiling      y = 2, normal -y, plain white.
  light        y = 1.98, x, z in [-0.4, 0.4], normal -y, Ke 10 10 10, no texture.
  card         z = 0, x in [-0.5, 0.5], y in [0.1, 1.1], normal +z; vt (0,0) at its
               bottom-left (-0.5, 0.1). card_alpha.png (RGBA, RGB white everywhere) is
               both map_Kd and map_d: 4 x 4 checks, opaque where floor(4u) + floor(4v)
               is even (the bottom-left check is opaque), alpha 0 elsewhere: half the
               card's area is transparent.
  metal_panel  a 0.36 x 0.5 vertical quad centred at (0.62, 0.3, 0.45), normal
               (-2, 0, 1)/sqrt(5) (it reflects the red wall towards the camera); Pm 1,
               map_Pr metal_roughness.png (grey): roughness = u, a gradient from 0
               (mirror) at the panel's left edge to 1 at its right edge. The PNG stores
               round(255 u) as data; a reader that decodes 8-bit maps from sRGB, as
               Blender 3.4 does (it sets no colour space on data maps), gets
               srgb_to_linear(u): still 0 to 1 and increasing, 0.21 in the middle.
Camera: eye (0, 0.75, 2.5) looking at the card's centre (0, 0.6, 0), vfov 45, 64 x 64:
the card fills about half the film's height and width, the panel is to its lower right
and occludes none of it; every pixel sees the box (no ray leaves by the open front).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from png_writer import srgb8, write_png  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE = 64  # every texture is SIZE x SIZE

MTL = """# Written by gen.py: the texture test scene's materials (maps as Blender 3.4 reads them).
newmtl floor_checker
Ka 0 0 0
Kd 0.8 0.8 0.8
Ks 0 0 0
map_Kd floor_checker.png

# -s 2 1 1: the stripes image repeats twice across the wall.
newmtl wall_stripes
Ka 0 0 0
Kd 0.8 0.8 0.8
Ks 0 0 0
map_Kd -s 2 1 1 wall_stripes.png

newmtl red
Ka 0 0 0
Kd 0.63 0.065 0.05
Ks 0 0 0

newmtl green
Ka 0 0 0
Kd 0.14 0.45 0.091
Ks 0 0 0

newmtl white
Ka 0 0 0
Kd 0.725 0.71 0.68
Ks 0 0 0

newmtl light
Ka 0 0 0
Kd 0 0 0
Ks 0 0 0
Ke 10 10 10

# One RGBA image for colour (white) and opacity (its alpha), as Blender's
# exporter writes a cut-out: rays ignore the card where alpha < 0.5.
newmtl card
Ka 0 0 0
Kd 1 1 1
Ks 0 0 0
map_Kd card_alpha.png
map_d card_alpha.png

# Pm 1: metal; the roughness map (linear data) replaces Pr 0.5.
newmtl textured_metal
Ka 0 0 0
Kd 0.9 0.9 0.9
Pm 1
Pr 0.5
map_Pr metal_roughness.png
"""


def texels(channels, f):
    """SIZE x SIZE rows, top first, of f(u, v) evaluated at the texel centres,
    where v = 0 is the bottom row (OBJ's and Blender's convention)."""
    rows = []
    for y in range(SIZE):
        v = 1.0 - (y + 0.5) / SIZE
        row = []
        for x in range(SIZE):
            px = f((x + 0.5) / SIZE, v)
            assert len(px) == channels
            row.extend(px)
        rows.append(row)
    return rows


def write_textures():
    cream = tuple(srgb8(c) for c in (0.80, 0.72, 0.52))
    blue = tuple(srgb8(c) for c in (0.04, 0.08, 0.30))
    write_png(os.path.join(HERE, "floor_checker.png"), SIZE, SIZE,
              texels(3, lambda u, v: cream if (int(8 * u) + int(8 * v)) % 2 == 0 else blue), 3)
    light_grey = tuple(srgb8(c) for c in (0.75, 0.75, 0.75))
    teal = tuple(srgb8(c) for c in (0.05, 0.30, 0.30))
    write_png(os.path.join(HERE, "wall_stripes.png"), SIZE, SIZE,
              texels(3, lambda u, v: light_grey if int(4 * u) % 2 == 0 else teal), 3)
    write_png(os.path.join(HERE, "card_alpha.png"), SIZE, SIZE,
              texels(4, lambda u, v: (255, 255, 255, 255 if (int(4 * u) + int(4 * v)) % 2 == 0 else 0)), 4)
    # Roughness is data, not colour: u itself, no sRGB curve.
    write_png(os.path.join(HERE, "metal_roughness.png"), SIZE, SIZE,
              texels(1, lambda u, v: (int(u * 255 + 0.5),)), 1)


def rect(origin, edge_u, edge_v):
    """The corners of origin + [0,1] edge_u + [0,1] edge_v, counter-clockwise
    seen from cross(edge_u, edge_v), with their vt: (0,0) (1,0) (1,1) (0,1)."""
    o, a, b = origin, edge_u, edge_v
    corners = [o, tuple(o[i] + a[i] for i in range(3)), tuple(o[i] + a[i] + b[i] for i in range(3)),
               tuple(o[i] + b[i] for i in range(3))]
    return corners, [(0, 0), (1, 0), (1, 1), (0, 1)]


def objects():
    s5 = math.sqrt(5.0)
    t = (1 / s5, 0.0, 2 / s5)  # the panel's horizontal edge; cross(t, +y) = (-2, 0, 1)/sqrt(5)
    pw, ph, pc = 0.36, 0.5, (0.62, 0.3, 0.45)
    panel_origin = (pc[0] - t[0] * pw / 2, pc[1] - ph / 2, pc[2] - t[2] * pw / 2)
    return [
        ("floor", "floor_checker", rect((-1, 0, 1), (2, 0, 0), (0, 0, -2))),
        ("back_wall", "wall_stripes", rect((-1, 0, -1), (2, 0, 0), (0, 2, 0))),
        ("left_wall", "red", rect((-1, 0, 1), (0, 0, -2), (0, 2, 0))),
        ("right_wall", "green", rect((1, 0, -1), (0, 0, 2), (0, 2, 0))),
        ("ceiling", "white", rect((-1, 2, -1), (2, 0, 0), (0, 0, 2))),
        ("light", "light", rect((-0.4, 1.98, -0.4), (0.8, 0, 0), (0, 0, 0.8))),
        ("card", "card", rect((-0.5, 0.1, 0), (1, 0, 0), (0, 1, 0))),
        ("metal_panel", "textured_metal", rect(panel_origin, (t[0] * pw, 0, t[2] * pw), (0, ph, 0))),
    ]


def num(x):
    # Short and exact where the value is: "-1", "0.5", "1.98"; never "-0".
    s = ("%.6f" % x).rstrip("0").rstrip(".")
    return "0" if s == "-0" else s


def main():
    write_textures()
    obj = ["# The texture test scene, written by gen.py (see its docstring for the layout).",
           "mtllib textured_box.mtl", ""]
    n = 0
    for name, material, (corners, uvs) in objects():
        obj += ["o " + name, "usemtl " + material]
        obj += ["v " + " ".join(num(c) for c in p) for p in corners]
        obj += ["vt %s %s" % (num(u), num(v)) for u, v in uvs]
        # One vt per vertex, in the same order: the indices agree.
        obj.append("f %d/%d %d/%d %d/%d" % (n + 1, n + 1, n + 2, n + 2, n + 3, n + 3))
        obj.append("f %d/%d %d/%d %d/%d" % (n + 1, n + 1, n + 3, n + 3, n + 4, n + 4))
        obj.append("")
        n += 4
    with open(os.path.join(HERE, "textured_box.obj"), "w") as f:
        f.write("\n".join(obj))
    with open(os.path.join(HERE, "textured_box.mtl"), "w") as f:
        f.write(MTL)
    scene = {"meshes": ["textured_box.obj"],
             "camera": {"eye": [0, 0.75, 2.5], "look_at": [0, 0.6, 0], "up": [0, 1, 0], "vfov_deg": 45},
             "environment": [0, 0, 0],
             "film": {"width": 64, "height": 64}}
    with open(os.path.join(HERE, "scene.json"), "w") as f:
        f.write("{\n" + ",\n".join("  %s: %s" % (json.dumps(k), json.dumps(v)) for k, v in scene.items()) + "\n}\n")


if __name__ == "__main__":
    main()
