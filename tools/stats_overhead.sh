#!/usr/bin/env bash
# Render time with statistics off and on (median of REPEAT runs of the same
# binary, interleaved so that drifts in machine load hit every variant), for
# each CELL_SAMPLES value of --cell-sample, and optionally against a BASELINE
# binary without the counting path (build/kappa-nostats, tools/check_baseline.sh):
#   BASELINE=build/kappa-nostats CELL_SAMPLES="auto 1" [THREADS=1] tools/stats_overhead.sh [SCENE.json ...]
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
repeat="${REPEAT:-5}"
size="${SIZE:-256}"
spp="${SPP:-32}"
read -r -a samples <<<"${CELL_SAMPLES:-auto}"
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=(assets/cornell-box/scene.json assets/bunny-lowres/scene_lowres.json)
  for s in bunny/scene.json sponza/scene.json; do
    [ -f "../shared/scenes/$s" ] && scenes+=("../shared/scenes/$s")
  done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

render_time() {  # binary, extra args...
  local bin=$1; shift
  "$bin" render "$scene" --spp "$spp" --width "$size" --height "$size" --out "$tmp/x.exr" ${THREADS:+--threads "$THREADS"} "$@" 2>&1 |
    sed -n 's/.*threads: \([0-9.]*\) s,.*/\1/p'
}
median() { printf "%s\n" "$@" | sort -g | sed -n "$((($# + 1) / 2))p"; }

printf "%-42s %8s" scene "off_s"
for k in "${samples[@]}"; do printf " %9s %7s" "on_s($k)" "on/off"; done
[ -n "${BASELINE:-}" ] && printf " %11s %12s" "baseline_s" "off/baseline"
printf "\n"
for scene in "${scenes[@]}"; do
  declare -A times=()
  for ((i = 0; i < repeat; ++i)); do
    times[off]+="$(render_time "$kappa" --stats off) "
    for k in "${samples[@]}"; do times[on_$k]+="$(render_time "$kappa" --stats on --cell-sample "$k") "; done
    [ -n "${BASELINE:-}" ] && times[base]+="$(render_time "$BASELINE") "
  done
  # shellcheck disable=SC2086
  off=$(median ${times[off]})
  printf "%-42s %8s" "$scene" "$off"
  for k in "${samples[@]}"; do
    # shellcheck disable=SC2086
    on=$(median ${times[on_$k]})
    printf " %9s %7.3f" "$on" "$(awk -v a="$on" -v b="$off" 'BEGIN{print a/b}')"
  done
  if [ -n "${BASELINE:-}" ]; then
    # shellcheck disable=SC2086
    base=$(median ${times[base]})
    printf " %11s %12.3f" "$base" "$(awk -v a="$off" -v b="$base" 'BEGIN{print a/b}')"
  fi
  printf "\n"
  unset times
done
