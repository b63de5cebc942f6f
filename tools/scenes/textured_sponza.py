#!/usr/bin/env python3
"""Writes a textured Dabrovic Sponza for the texture and environment-light work:
the shared Sponza (../shared/scenes/sponza: sponza.obj, sponza.mtl, scene.json)
with a procedural colour map on every material, three cut-out banners hanging
in the atrium, and the daylight sky of assets/sky as its environment.

    python3 tools/scenes/textured_sponza.py [--sponza DIR] [--out DIR]
        --sponza  the shared Sponza (default: ../shared/scenes/sponza from the repository root)
        --out     where to write (default: build/scenes/sponza-textured in the repository)
    (run python3 assets/sky/gen.py first if assets/sky/sky.hdr is missing)

Writes into --out:
  sponza.obj           the original's lines unchanged except `mtllib sponza_textured.mtl`,
                       then `g banner` / `usemtl banner`: three vertical 1.2 x 2.4 m quads
                       (two triangles each, vt (0,0) at the bottom left, normal -x: facing
                       the shared camera), placed from the bounds of the v lines and checked
                       to touch no original triangle's bounding box
  sponza_textured.mtl  every original material with its lines (Ka, Kd, Ks) kept and a map_Kd
                       chosen by its group's name: brick for walls, stone blocks for pillars,
                       arcs and the other masonry, tiles for floors, planks for doors and
                       windows, plaster for the ceiling; `-s su sv 1` where the group's vt
                       span several texture tiles (see below); plus `banner`: map_Kd and map_d
                       one RGBA image (a red banner with a gold emblem, a swallowtail fringe
                       and holes: its alpha is 0 or 255)
  brick.png, stone.png, tiles.png, wood.png, plaster.png   256 x 256 RGB, sRGB, tileable
  banner.png           128 x 256 RGBA (RGB under the holes is the banner's red, so that
                       filtering at a hole's edge does not darken it)
  scene.json           the shared one with "meshes": ["sponza.obj"] and "environment": "sky.hdr"
  sky.hdr              a copy of assets/sky/sky.hdr

Kappa's scene.json accepts "environment": "FILE.hdr" (a path relative to the JSON file) as well
as a constant [r, g, b]: a Radiance latitude-longitude map, row 0 straight up (+y), the middle
row the horizon, the centre column looking along +x and u growing towards +z (the orientation
assets/sky/gen.py's docstring gives). sky.hdr's sun stands 35 degrees high towards
(0.25, 0.57, -0.78): over the building's -z side, so in the narrow atrium it lights only the
top few metres of the +z side's walls; the rest is lit by the sky and by bounced sunlight.

Sponza's texture coordinates are those of its Max2Obj export: every face has vt (third
component 0), but they are not normalised: the floors span u -4.9..5.9, the walls
u -4.6..5.6 and v 0..7, the parapet v -10.1..11.1, with about 2-3 m of the building per
unit of vt. So the scale is measured per group (the area-weighted median length of dP/du
and dP/dv over its triangles, in metres per unit of u and v) and -s is that length over
the world size one texture tile should cover (TILE_M), rounded, at least 1. About 45 %
of the ceiling's triangles (and many in object21 and object4) have degenerate vt (zero
area): they take one texel's colour, hence plaster there.
"""
import argparse
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "assets"))
from png_writer import srgb8, write_png  # noqa: E402

SKY = os.path.join(ROOT, "assets", "sky", "sky.hdr")
TEX = 256

# World size (metres, along u and v) one tile of each texture should cover:
# brick 4 bricks x 16 courses (0.25 x 0.075 m), stone 2 blocks x 4 courses
# (0.8 x 0.4 m), tiles 4 x 4 (0.4 m), wood 8 planks (0.3 m).
TILE_M = {"brick": (1.0, 1.2), "stone": (1.6, 1.6), "tiles": (1.6, 1.6), "wood": (2.4, 2.4),
          "plaster": (2.0, 2.0)}

BANNER_W, BANNER_H = 1.2, 2.4  # the banner image's aspect: 128 x 256


def category(group):
    """The texture a group gets, by its name (Sponza's groups are named by part)."""
    if group in ("doors", "windows"):
        return "wood"
    if group == "floors":  # arcs_floor_* and pillar_floor are masonry at floor level, not floors
        return "tiles"
    if group in ("walls", "outside01"):
        return "brick"
    if group == "ceiling":
        return "plaster"
    return "stone"  # pillar*, puillar_floor_corner (sic), arcs*, parapet, relief, holes, object*


# ---------------------------------------------------------------- procedural textures

def hash01(x, y, seed):
    """A deterministic hash of integer lattice points to [0, 1) (not Python's hash)."""
    h = (x * 374761393 + y * 668265263 + seed * 2246822519) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return (h ^ (h >> 16)) / 4294967296.0


def noise(x, y, cells, seed):
    """Value noise in [0, 1] over pixel (x, y) of a TEX-wide image with `cells`
    lattice cells across, wrapping so the texture tiles."""
    fx, fy = x * cells / TEX, y * cells / TEX
    ix, iy = int(fx), int(fy)
    tx, ty = fx - ix, fy - iy
    tx, ty = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)
    x0, x1, y0, y1 = ix % cells, (ix + 1) % cells, iy % cells, (iy + 1) % cells
    a = hash01(x0, y0, seed) + tx * (hash01(x1, y0, seed) - hash01(x0, y0, seed))
    b = hash01(x0, y1, seed) + tx * (hash01(x1, y1, seed) - hash01(x0, y1, seed))
    return a + ty * (b - a)


def fbm(x, y, cells, seed, octaves=3):
    total, amp, norm = 0.0, 1.0, 0.0
    for o in range(octaves):
        total += amp * noise(x, y, cells << o, seed + o)
        norm += amp
        amp *= 0.5
    return total / norm


def mix(a, b, t):
    return tuple(a[i] + t * (b[i] - a[i]) for i in range(3))


def scale(c, s):
    return tuple(ch * s for ch in c)


def brick(x, y):
    course = y // 16
    xs = x + (32 if course % 2 else 0)  # running bond: every other course shifted half a brick
    if y % 16 < 2 or xs % 64 < 2:
        return scale((0.62, 0.60, 0.55), 0.9 + 0.2 * fbm(x, y, 32, 11))
    b = hash01((xs // 64) % 4, course, 12)
    return scale(mix((0.45, 0.20, 0.12), (0.62, 0.36, 0.22), b), 0.85 + 0.3 * fbm(x, y, 16, 13))


def stone(x, y):
    course = y // 64
    xs = x + (64 if course % 2 else 0)
    if y % 64 < 3 or xs % 128 < 3:
        return (0.30, 0.28, 0.25)
    b = hash01((xs // 128) % 2, course, 21)
    return scale((0.68, 0.62, 0.50), (0.88 + 0.24 * b) * (0.85 + 0.3 * fbm(x, y, 8, 22)))


def tiles(x, y):
    if x % 64 < 2 or y % 64 < 2:
        return (0.40, 0.38, 0.35)
    light = (x // 64 + y // 64) % 2 == 0
    # Marble-ish veins: a sine bent by noise.
    vein = 0.5 + 0.5 * math.sin(2 * math.pi * (x + y) / 64 + 6 * fbm(x, y, 8, 31))
    base = (0.72, 0.68, 0.60) if light else (0.28, 0.24, 0.20)
    return scale(base, 0.88 + 0.12 * vein)


def wood(x, y):
    if x % 32 == 0:
        return (0.08, 0.05, 0.03)  # the gap between planks
    plank = x // 32
    b = hash01(plank, 0, 41)
    # Grain along v (planks stand upright on the doors): stripes across the plank, wavy.
    grain = 0.5 + 0.5 * math.sin(2 * math.pi * (3 * (x % 32) / 32 + 2 * fbm(x, y, 4, 42 + plank) + b))
    return scale((0.36, 0.20, 0.10), (0.85 + 0.3 * b) * (0.85 + 0.15 * grain))


def plaster(x, y):
    return scale((0.74, 0.71, 0.65), 0.93 + 0.14 * fbm(x, y, 16, 51))


BANNER_PX = (128, 256)
RED, GOLD = (0.40, 0.03, 0.03), (0.75, 0.55, 0.12)


def banner(x, y):
    """(linear rgb, alpha) at pixel (x, y), y from the top."""
    w, h = BANNER_PX
    yb = h - 1 - y  # from the bottom
    cx = x + 0.5 - w / 2
    # Swallowtail: the lower edge rises from 24 px at the sides to 80 px in the
    # middle; a fringe of 2-px strands hangs 24 px below it.
    edge = 24 + 56 * (1 - abs(cx) / (w / 2))
    if yb < edge - 24:
        return RED, 0
    if yb < edge:
        return (GOLD, 255) if x % 4 < 2 else (RED, 0)
    # Three round holes in a row.
    for hx in (32, 64, 96):
        if (x + 0.5 - hx) ** 2 + (yb + 0.5 - 120) ** 2 < 8 ** 2:
            return RED, 0
    # The emblem: a gold ring whose inside is cut out except for a gold diamond.
    r = math.hypot(cx, yb + 0.5 - 180)
    if 30 <= r < 38:
        return GOLD, 255
    if r < 30:
        return (GOLD, 255) if abs(cx) + abs(yb + 0.5 - 180) < 16 else (RED, 0)
    if x < 6 or x >= w - 6 or y < 6 or edge <= yb < edge + 6:
        return GOLD, 255  # border
    return RED, 255


def write_textures(out):
    """Writes the PNGs; returns {name: (size, mean linear albedo)} for the report."""
    made = {}
    for name, f in (("brick", brick), ("stone", stone), ("tiles", tiles), ("wood", wood), ("plaster", plaster)):
        rows, total = [], [0.0, 0.0, 0.0]
        for y in range(TEX):
            row = []
            for x in range(TEX):
                c = f(x, y)
                total = [total[i] + c[i] for i in range(3)]
                row.extend(srgb8(ch) for ch in c)
            rows.append(row)
        write_png(os.path.join(out, name + ".png"), TEX, TEX, rows, 3)
        made[name] = ("%d x %d RGB" % (TEX, TEX), tuple(t / TEX ** 2 for t in total))
    w, h = BANNER_PX
    rows, holes = [], 0
    for y in range(h):
        row = []
        for x in range(w):
            c, a = banner(x, y)
            holes += a == 0
            row.extend([srgb8(ch) for ch in c] + [a])
        rows.append(row)
    write_png(os.path.join(out, "banner.png"), w, h, rows, 4)
    made["banner"] = ("%d x %d RGBA, %.1f %% transparent" % (w, h, 100.0 * holes / (w * h)), None)
    return made


# ---------------------------------------------------------------- the OBJ

def read_obj(path):
    """The OBJ's lines (exactly as read) and what the textures need: counts of v
    and vt, the bounds, and per group the triangles' (area, |dP/du|, |dP/dv|)."""
    with open(path, newline="") as f:
        lines = f.readlines()
    v, vt, groups, group = [], [], {}, None
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for line in lines:
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            q = tuple(float(c) for c in p[1:4])
            v.append(q)
            lo = [min(lo[i], q[i]) for i in range(3)]
            hi = [max(hi[i], q[i]) for i in range(3)]
        elif p[0] == "vt":
            vt.append((float(p[1]), float(p[2])))
        elif p[0] == "g":
            group = " ".join(p[1:])
            groups.setdefault(group, {"faces": 0, "no_vt": 0, "flat_vt": 0, "jac": []})
        elif p[0] == "f":
            g = groups.setdefault(group, {"faces": 0, "no_vt": 0, "flat_vt": 0, "jac": []})
            g["faces"] += 1
            refs = [r.split("/") for r in p[1:]]
            if any(len(r) < 2 or r[1] == "" for r in refs):
                g["no_vt"] += 1
                continue
            P = [v[int(r[0]) - 1] for r in refs]  # Sponza's indices are all positive
            T = [vt[int(r[1]) - 1] for r in refs]
            # Triangle fan for polygons (Sponza has only triangles).
            for k in range(1, len(refs) - 1):
                e1 = [P[k][i] - P[0][i] for i in range(3)]
                e2 = [P[k + 1][i] - P[0][i] for i in range(3)]
                du1, dv1 = T[k][0] - T[0][0], T[k][1] - T[0][1]
                du2, dv2 = T[k + 1][0] - T[0][0], T[k + 1][1] - T[0][1]
                cr = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
                area = 0.5 * math.sqrt(sum(c * c for c in cr))
                det = du1 * dv2 - du2 * dv1
                if abs(det) < 1e-9 or area == 0:
                    g["flat_vt"] += 1
                    continue
                dpdu = [(dv2 * e1[i] - dv1 * e2[i]) / det for i in range(3)]
                dpdv = [(du1 * e2[i] - du2 * e1[i]) / det for i in range(3)]
                g["jac"].append((area, math.sqrt(sum(c * c for c in dpdu)), math.sqrt(sum(c * c for c in dpdv))))
    return lines, len(v), len(vt), (lo, hi), groups


def weighted_median(pairs):
    """The median of values weighted by areas: pairs of (area, value). The median,
    not the mean: a few nearly degenerate vt triangles stretch to kilometres."""
    pairs = sorted(pairs, key=lambda p: p[1])
    half, acc = sum(a for a, _ in pairs) / 2, 0.0
    for a, val in pairs:
        acc += a
        if acc >= half:
            return val
    return 1.0


def banners(bounds):
    """Three banners hung in the open middle of the building: along its long axis (x)
    at -23 %, 0 and +23 % of its half length, staggered across (z) so that each is seen
    from the shared camera on the axis at x = -13.5, and higher the farther they hang
    (33 %, 39 %, 45 % of the height above the lowest point) so all stay in its view."""
    lo, hi = bounds
    c = [(lo[i] + hi[i]) / 2 for i in range(3)]
    half_x, half_z, height = (hi[0] - lo[0]) / 2, (hi[2] - lo[2]) / 2, hi[1] - lo[1]
    quads = []
    for fx, fz, fy in ((-0.23, -0.18, 0.33), (0.0, 0.18, 0.39), (0.23, 0.0, 0.45)):
        # Rounded to the centimetre: tidy OBJ lines, and the same ones for a re-exported Sponza.
        x, zc, y0 = (round(c[0] + fx * half_x, 2), round(c[2] + fz * half_z, 2), round(lo[1] + fy * height, 2))
        z0, z1, y1 = zc - BANNER_W / 2, zc + BANNER_W / 2, y0 + BANNER_H
        # Counter-clockwise seen from -x: bottom left (z0), bottom right (z1), top right, top left;
        # cross(v1 - v0, v2 - v0) = (-(z1 - z0) * (y1 - y0), 0, 0) points to -x.
        quads.append([(x, y0, z0), (x, y0, z1), (x, y1, z1), (x, y1, z0)])
    return quads


def clearance(lines, quads, margin=0.05):
    """How many original triangles have a bounding box within `margin` of a banner's."""
    boxes = [([min(p[i] for p in q) - margin for i in range(3)], [max(p[i] for p in q) + margin for i in range(3)])
             for q in quads]
    v, hits = [], 0
    for line in lines:
        if line.startswith("v "):
            v.append(tuple(float(c) for c in line.split()[1:4]))
        elif line.startswith("f "):
            P = [v[int(r.split("/")[0]) - 1] for r in line.split()[1:]]
            tlo = [min(p[i] for p in P) for i in range(3)]
            thi = [max(p[i] for p in P) for i in range(3)]
            hits += any(all(thi[i] >= blo[i] and tlo[i] <= bhi[i] for i in range(3)) for blo, bhi in boxes)
    return hits


def read_mtl(path):
    """{name: [lines after newmtl]} in file order, the lines without blank ones."""
    materials, current = {}, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if s.startswith("newmtl "):
                current = s[7:].strip()
                materials[current] = []
            elif current is not None and s and not s.startswith("#"):
                materials[current].append(s)
    return materials


def fmt(x):
    s = ("%.6f" % x).rstrip("0").rstrip(".")
    return "0" if s == "-0" else s


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sponza", default=os.path.join(ROOT, "..", "shared", "scenes", "sponza"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "scenes", "sponza-textured"))
    a = ap.parse_args()
    a.sponza, a.out = os.path.normpath(a.sponza), os.path.normpath(a.out)
    if not os.path.exists(SKY):
        sys.exit("textured_sponza.py: %s is missing: run python3 assets/sky/gen.py" % SKY)
    os.makedirs(a.out, exist_ok=True)

    lines, nv, nvt, bounds, groups = read_obj(os.path.join(a.sponza, "sponza.obj"))
    materials = read_mtl(os.path.join(a.sponza, "sponza.mtl"))
    no_vt = sum(g["no_vt"] for g in groups.values())
    quads = banners(bounds)
    hits = clearance(lines, quads)
    if hits:
        sys.exit("textured_sponza.py: the banners touch %d triangles' bounding boxes; move them" % hits)

    made = write_textures(a.out)

    # The MTL: each original material as it was, plus its map.
    mtl = ["# Written by tools/scenes/textured_sponza.py: Sponza's materials (Kd kept, map_Kd",
           "# replaces it) with procedural colour maps; -s from each group's metres per unit of vt.", ""]
    textured = 0
    for name, body in materials.items():
        kind = category(name)
        g = groups.get(name)
        mtl.append("newmtl " + name)
        mtl += body
        if g and g["jac"]:
            mu = weighted_median([(area, lu) for area, lu, _ in g["jac"]])
            mv = weighted_median([(area, lv) for area, _, lv in g["jac"]])
            su = max(1, int(round(mu / TILE_M[kind][0])))
            sv = max(1, int(round(mv / TILE_M[kind][1])))
            mtl.append("# %s: %.2f m per unit of u, %.2f of v" % (kind, mu, mv))
        else:
            su = sv = 1
        opt = "" if (su, sv) == (1, 1) else "-s %d %d 1 " % (su, sv)
        mtl += ["map_Kd %s%s.png" % (opt, kind), ""]
        textured += 1
    mtl += ["# A cut-out: one RGBA image for colour and opacity (rays ignore alpha < 0.5).",
            "newmtl banner", "Ka 0 0 0", "Kd 0.4 0.03 0.03", "Ks 0 0 0",
            "map_Kd banner.png", "map_d banner.png", ""]
    with open(os.path.join(a.out, "sponza_textured.mtl"), "w") as f:
        f.write("\n".join(mtl))

    # The OBJ: the original's lines, its mtllib replaced, then the banners.
    with open(os.path.join(a.out, "sponza.obj"), "w", newline="") as f:
        replaced = 0
        for line in lines:
            if line.split()[:1] == ["mtllib"]:
                line = "mtllib sponza_textured.mtl" + line[len(line.rstrip("\r\n")):]
                replaced += 1
            f.write(line)
        if replaced != 1:
            sys.exit("textured_sponza.py: expected one mtllib line in sponza.obj, found %d" % replaced)
        if lines and not lines[-1].endswith("\n"):
            f.write("\n")
        f.write("# Appended by tools/scenes/textured_sponza.py: %d banner cards of %g x %g m, "
                "2 triangles each, vt per vertex.\n" % (len(quads), BANNER_W, BANNER_H))
        f.write("g banner\nusemtl banner\ns off\n")
        for q in quads:
            for p in q:
                f.write("v %s\n" % " ".join(fmt(c) for c in p))
        for _ in quads:
            f.write("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n")
        for k in range(len(quads)):
            i, t = nv + 4 * k, nvt + 4 * k
            f.write("f %d/%d %d/%d %d/%d\n" % (i + 1, t + 1, i + 2, t + 2, i + 3, t + 3))
            f.write("f %d/%d %d/%d %d/%d\n" % (i + 1, t + 1, i + 3, t + 3, i + 4, t + 4))

    with open(os.path.join(a.sponza, "scene.json")) as f:
        scene = json.load(f)
    scene["meshes"] = ["sponza.obj"]
    scene["environment"] = "sky.hdr"
    with open(os.path.join(a.out, "scene.json"), "w") as f:
        f.write("{\n" + ",\n".join("  %s: %s" % (json.dumps(k), json.dumps(v)) for k, v in scene.items()) + "\n}\n")
    with open(SKY, "rb") as fi, open(os.path.join(a.out, "sky.hdr"), "wb") as fo:
        fo.write(fi.read())

    # The report.
    lo, hi = bounds
    print("read %s: %d v, %d vt, %d faces in %d groups, %d faces without vt" % (
        a.sponza, nv, nvt, sum(g["faces"] for g in groups.values()), len(groups), no_vt))
    print("bounds x %.2f..%.2f, y %.2f..%.2f, z %.2f..%.2f" % (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]))
    print("wrote %s:" % a.out)
    print("  sponza_textured.mtl: %d materials textured + banner" % textured)
    for name, (size, mean) in made.items():
        extra = "" if mean is None else ", mean linear albedo (%.2f, %.2f, %.2f)" % mean
        print("  %s.png: %s%s" % (name, size, extra))
    print("  sponza.obj: + %d banner triangles (%d cards), clear of every original triangle's box:"
          % (2 * len(quads), len(quads)))
    for q in quads:
        print("    x = %.2f, y %.2f..%.2f, z %.2f..%.2f, normal -x" % (q[0][0], q[0][1], q[2][1], q[0][2], q[1][2]))
    print("  scene.json (environment sky.hdr), sky.hdr")


if __name__ == "__main__":
    main()
