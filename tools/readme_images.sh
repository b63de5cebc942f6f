#!/usr/bin/env bash
# The README's pictures: the Cornell box rendered, and its cell map
# (per-cell ray visits p in red, triangles Theta in green, summed along y) on
# a 64^3 grid, so that the map has cells enough to show the boxes; the
# material test scene, Veach's MIS scene and the textured box (textures,
# cut-outs) rendered; with ../shared, the textured Sponza under the sky image.
#   tools/readme_images.sh    (after tools/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/kappa render assets/cornell-box/scene.json --spp 256 --width 400 --height 400 --grid-res 64 -q \
  --out "$tmp/cornell-box.exr" --cell-map docs/images/cornell-box-cells.png
build/exr_to_png "$tmp/cornell-box.exr" docs/images/cornell-box.png
build/kappa render assets/material-box/scene.json --spp 256 --width 400 --height 400 -q --out "$tmp/material-box.exr"
build/exr_to_png "$tmp/material-box.exr" docs/images/material-box.png
build/kappa render assets/veach-mis/scene.json --spp 256 --width 400 --height 300 -q --out "$tmp/veach-mis.exr"
build/exr_to_png "$tmp/veach-mis.exr" docs/images/veach-mis.png
build/kappa render assets/textured-box/scene.json --spp 256 --width 400 --height 400 -q --out "$tmp/textured-box.exr" \
  --preview docs/images/textured-box.png
if [ -d ../shared/scenes/sponza ]; then
  python3 tools/scenes/textured_sponza.py --out "$tmp/sponza-textured" > /dev/null
  build/kappa render "$tmp/sponza-textured/scene.json" --spp 256 --width 400 --height 400 -q \
    --out "$tmp/sponza-textured.exr" --preview docs/images/sponza-textured.png
fi
