#!/usr/bin/env bash
# grid2's densities against the speed they give: for each top density (top
# cells per triangle) and leaf density (sub-grid cells per triangle of a top
# cell), one `kappa bench` run of grid, grid2 and Embree taking turns on the
# same camera, bounce and shadow rays, 1 thread; prints each class's
# grid2 / Embree and grid2 / grid speed ratios (same-run ratios, which the
# machine's drift cancels out of) and grid2's build time and bytes. The
# measurement behind kDefaultGrid2TopDensity and kDefaultGrid2LeafDensity.
#
#   tools/grid2_density_sweep.sh [SCENE.json ...]
#
# Environment: TOPS (default "0.015625 0.0625 0.125 0.25 1"), LEAVES (default
# "1 2 4 8 16"), N (rays per class, default 65536), REPEAT (default 3).
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
tops="${TOPS:-0.015625 0.0625 0.125 0.25 1}"
leaves="${LEAVES:-1 2 4 8 16}"
n="${N:-65536}"
repeat="${REPEAT:-3}"
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=(assets/cornell-box/scene.json assets/bunny-lowres/scene_lowres.json)
  for s in sponza/scene.json bunny/scene.json teapot-in-stadium/scene.json; do
    [ -f "../shared/scenes/$s" ] && scenes+=("../shared/scenes/$s")
  done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "uptime before: $(uptime)"
printf "%-42s %9s %5s | %-26s | %-26s | %8s %10s\n" scene top leaf "grid2/embree cam bnc shd" "grid2/grid cam bnc shd" build_s MB
for scene in "${scenes[@]}"; do
  for top in $tops; do
    for leaf in $leaves; do
      "$kappa" bench "$scene" --accel grid,grid2,embree --rays camera,bounce,shadow --threads 1 --repeat "$repeat" \
        --n "$n" --grid2-top-density "$top" --grid2-leaf-density "$leaf" --json "$tmp/b.json" > /dev/null
      /usr/bin/python3 - "$tmp/b.json" "$scene" "$top" "$leaf" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
rows = {(r["accel"], r["rays"]): r for r in j["results"] if r["threads"] == 1}
classes = ["camera", "bounce", "shadow"]
to_embree = " ".join("%.3f" % rows[("grid2", c)]["ratio_to_embree"] for c in classes)
to_grid = " ".join("%.3f" % (rows[("grid2", c)]["mrays_per_s_median"] / rows[("grid", c)]["mrays_per_s_median"]) for c in classes)
a = j["accels"]["grid2"]
print("%-42s %9s %5s | %-26s | %-26s | %8.3f %10.1f" % (sys.argv[2][-42:], sys.argv[3], sys.argv[4], to_embree, to_grid,
                                                       a["build_s"], a["bytes"] / 2**20))
PY
    done
  done
done
echo "uptime after: $(uptime)"
