#!/usr/bin/env python3
"""A daylight environment map for image-based lighting: a sky gradient, a dim
ground and a small, very bright sun that holds most of the map's light, so
that a renderer sampling the environment uniformly is visibly noisier than
one sampling it by importance.

    python3 assets/sky/gen.py    # writes sky.hdr (256 x 128), prints the sun's share

The file: Radiance RGBE (.hdr), flat scanlines, header "-Y 128 +X 256" (the
first row stored is the top one), linear radiance, no exposure.

Orientation (latitude-longitude, equirectangular; y up as in the scenes):
  pixel (column c, row r) covers u in [c, c+1)/256 and v in [r, r+1)/128;
  theta = pi * v is the angle from +y (row 0 at the top is straight up, the
  horizon is the edge between rows 63 and 64, the last row straight down);
  phi = 2 * pi * u is the azimuth, measured from -x towards -z: the direction is
      d = (-sin(theta) cos(phi), cos(theta), -sin(theta) sin(phi)),
  so u = 0 looks along -x, u = 0.25 along -z, u = 0.5 (the centre column) along +x,
  u = 0.75 along +z, and a direction d is found at u = 0.5 + atan2(d.z, d.x) / (2 pi),
  v = acos(d.y) / pi. This is Kappa's convention (renderer/render/environment_map.h:
  the centre column looks along +x, u grows towards +z, as Blender's world shows an
  image to a Y-up export), with its environment_rotation_deg at 0.

Content: above the horizon a gradient from (0.30, 0.42, 0.60) at the zenith to
(0.70, 0.74, 0.78) at the horizon; below it a brownish grey from (0.10, 0.085,
0.065) at the horizon to (0.05, 0.045, 0.04) straight down; the sun a disc of
radius 3 degrees centred at elevation 35 degrees, u = 0.3 (direction printed),
radiance (2200, 2000, 1700), its edge pixels covered partly (8 x 8 samples a
pixel). The share printed is the sun's part of sum(luminance * sin(theta)) over
the pixels (Rec. 709 luminance; sin(theta) at the pixel centre is the pixel's
solid angle up to a constant): the distribution an importance sampler draws.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from png_writer import write_hdr  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
W, H = 256, 128
ZENITH, HORIZON = (0.30, 0.42, 0.60), (0.70, 0.74, 0.78)
GROUND_HORIZON, NADIR = (0.10, 0.085, 0.065), (0.05, 0.045, 0.04)
SUN_U, SUN_ELEVATION_DEG, SUN_RADIUS_DEG = 0.3, 35.0, 3.0
SUN = (2200.0, 2000.0, 1700.0)
SUPERSAMPLE = 8


def direction(u, v):
    theta, phi = math.pi * v, 2 * math.pi * u
    return (-math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))


def luminance(c):
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


def sky(v):
    """The sky and ground without the sun, at v (a function of elevation only)."""
    elevation = math.pi / 2 - math.pi * v
    if elevation >= 0:
        # Paler towards the horizon; the square keeps the blue over most of the dome.
        t = (1 - math.sin(elevation)) ** 2
        return tuple(ZENITH[i] + t * (HORIZON[i] - ZENITH[i]) for i in range(3))
    t = math.sin(-elevation)
    return tuple(GROUND_HORIZON[i] + t * (NADIR[i] - GROUND_HORIZON[i]) for i in range(3))


def main():
    sun_dir = direction(SUN_U, 0.5 - SUN_ELEVATION_DEG / 180.0)
    cos_radius = math.cos(math.radians(SUN_RADIUS_DEG))
    # Pixels farther than this from the sun's centre cannot touch its disc:
    # the disc's radius plus a pixel's diagonal (in the worst row, near the sun).
    near = math.cos(math.radians(SUN_RADIUS_DEG + 2 * 360.0 / W))
    rows, total, sun_weight = [], 0.0, 0.0
    for r in range(H):
        v = (r + 0.5) / H
        base = sky(v)
        sin_theta = math.sin(math.pi * v)
        row = []
        for c in range(W):
            u = (c + 0.5) / W
            d = direction(u, v)
            cover = 0.0
            if sum(d[i] * sun_dir[i] for i in range(3)) > near:
                inside = 0
                for j in range(SUPERSAMPLE):
                    for i in range(SUPERSAMPLE):
                        ds = direction((c + (i + 0.5) / SUPERSAMPLE) / W, (r + (j + 0.5) / SUPERSAMPLE) / H)
                        inside += sum(ds[k] * sun_dir[k] for k in range(3)) >= cos_radius
                cover = inside / SUPERSAMPLE ** 2
            px = tuple(base[i] + cover * (SUN[i] - base[i]) for i in range(3))
            row.extend(px)
            total += luminance(px) * sin_theta
            sun_weight += cover * (luminance(SUN) - luminance(base)) * sin_theta
        rows.append(row)
    write_hdr(os.path.join(HERE, "sky.hdr"), W, H, rows)
    print("sky.hdr: %d x %d; sun at u = %.2f, elevation %.0f deg, direction (%.4f, %.4f, %.4f)"
          % ((W, H, SUN_U, SUN_ELEVATION_DEG) + sun_dir))
    print("sun's share of sum(luminance * sin(theta)): %.1f %%" % (100 * sun_weight / total))


if __name__ == "__main__":
    main()
