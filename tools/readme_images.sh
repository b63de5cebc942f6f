#!/usr/bin/env bash
# The README's two pictures: the Cornell box rendered, and its cell map
# (per-cell ray visits p in red, triangles Theta in green, summed along y) on
# a 64^3 grid, so that the map has cells enough to show the boxes.
#   tools/readme_images.sh    (after tools/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/kappa render assets/cornell-box/scene.json --spp 256 --width 400 --height 400 --grid-res 64 -q \
  --out "$tmp/cornell-box.exr" --cell-map docs/images/cornell-box-cells.png
build/exr_to_png "$tmp/cornell-box.exr" docs/images/cornell-box.png
