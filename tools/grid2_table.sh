#!/usr/bin/env bash
# The accelerators' table (docs/accelerators.md): per shared scene, one
# `kappa bench` run with grid, grid2 and both Embrees taking turns on the same
# camera, bounce and shadow rays (1 thread, REPEAT repeats, the median of
# each), printing grid / Embree, grid2 / Embree, grid2 / embree-fast and
# grid2 / grid per class (same-run ratios) and each structure's build time
# and bytes, with `uptime` before and after.
#
#   tools/grid2_table.sh [SCENE.json ...]     (default: every ../shared/scenes/*/scene*.json)
#
# Environment: N (rays per class, default 65536), REPEAT (default 5), THREADS (default 1),
# CPU (with THREADS=1, the core every bench runs on; default the last one; "none" to
# let the kernel choose). Pinned, because the cores of these machines are not alike
# for memory-bound walks: on 2026-12-06 the uniform grid's bunny camera rays ran
# 1.75x slower on cpu 0 than on cpu 1 (grid2 1.33x, Embree 1.04x), so a bench that
# migrated between them mid-run gave grid / Embree 0.098 instead of 0.154.
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
n="${N:-65536}" repeat="${REPEAT:-5}" threads="${THREADS:-1}"
pin=()
if [ "$threads" = 1 ] && [ "${CPU:-}" != none ] && command -v taskset > /dev/null; then
  pin=(taskset -c "${CPU:-$(($(nproc) - 1))}")
fi
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  for s in ../shared/scenes/*/scene*.json; do
    case "$s" in */malformed/*) continue ;; esac
    [ -f "$s" ] && scenes+=("$s")
  done
fi
[ ${#scenes[@]} -gt 0 ] || { echo "grid2_table.sh: no scenes (../shared/scenes is absent)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "uptime before: $(uptime)"
[ ${#pin[@]} -eq 0 ] || echo "pinned: ${pin[*]}"
echo
echo "| scene | grid ÷ Embree (cam, bnc, shd) | grid2 ÷ Embree (cam, bnc, shd) | grid2 ÷ embree-fast (cam, bnc, shd) | grid2 ÷ grid (cam, bnc, shd) | build s grid / grid2 / Embree / fast | MB grid / grid2 / Embree / fast |"
echo "|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  "${pin[@]}" "$kappa" bench "$scene" --accel grid,grid2,embree,embree-fast --rays camera,bounce,shadow --threads "$threads" \
    --repeat "$repeat" --n "$n" --json "$tmp/b.json" > /dev/null 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
  /usr/bin/python3 - "$tmp/b.json" "$scene" "$threads" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
t = int(sys.argv[3])
rows = {(r["accel"], r["rays"]): r for r in j["results"] if r["threads"] == t}
classes = ["camera", "bounce", "shadow"]
def ratios(a, b):
    return ", ".join("%.3f" % (rows[(a, c)]["mrays_per_s_median"] / rows[(b, c)]["mrays_per_s_median"]) for c in classes)
acc = j["accels"]
name = sys.argv[2].split("/scenes/")[-1].replace(".json", "")
names = ["grid", "grid2", "embree", "embree-fast"]
print("| %s | %s | %s | %s | %s | %s | %s |" % (
    name, ratios("grid", "embree"), ratios("grid2", "embree"), ratios("grid2", "embree-fast"), ratios("grid2", "grid"),
    " / ".join("%.3f" % acc[a]["build_s"] for a in names), " / ".join("%.1f" % (acc[a]["bytes"] / 2**20) for a in names)))
PY
done
echo
echo "uptime after: $(uptime)"
