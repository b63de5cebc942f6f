#!/usr/bin/env bash
# Render time with statistics on vs off (median of REPEAT runs, same binary),
# and optionally against a BASELINE binary built without the stats module:
#   BASELINE=/path/to/old/build/kappa tools/stats_overhead.sh [SCENE.json ...]
set -euo pipefail
cd "$(dirname "$0")/.."
repeat="${REPEAT:-3}"
size="${SIZE:-256}"
spp="${SPP:-8}"
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=(assets/cornell-box/scene.json assets/bunny-lowres/scene_lowres.json)
  for s in bunny/scene.json sponza/scene.json; do
    [ -f "../shared/scenes/$s" ] && scenes+=("../shared/scenes/$s")
  done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median_time() {  # binary, extra args...
  local bin=$1; shift
  local times=()
  for ((i = 0; i < repeat; ++i)); do
    times+=("$("$bin" render "$scene" --spp "$spp" --width "$size" --height "$size" --out "$tmp/x.exr" "$@" 2>&1 |
      sed -n 's/.*threads: \([0-9.]*\) s,.*/\1/p')")
  done
  printf "%s\n" "${times[@]}" | sort -g | sed -n "$(((repeat + 1) / 2))p"
}

printf "%-45s %9s %9s %8s" scene "off_s" "on_s" "on/off"
[ -n "${BASELINE:-}" ] && printf " %11s %12s" "baseline_s" "off/baseline"
printf "\n"
for scene in "${scenes[@]}"; do
  off=$(median_time build/kappa --stats off)
  on=$(median_time build/kappa --stats on)
  printf "%-45s %9s %9s %8.3f" "$scene" "$off" "$on" "$(awk -v a="$on" -v b="$off" 'BEGIN{print a/b}')"
  if [ -n "${BASELINE:-}" ]; then
    base=$(median_time "$BASELINE")
    printf " %11s %12.3f" "$base" "$(awk -v a="$off" -v b="$base" 'BEGIN{print a/b}')"
  fi
  printf "\n"
done
