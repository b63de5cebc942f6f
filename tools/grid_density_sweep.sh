#!/usr/bin/env bash
# Renders scenes with the grid at several densities (lambda in N_c = lambda*N)
# and prints the render time of each: the measurement behind the default
# --grid-density. Usage: tools/grid_density_sweep.sh [SCENE.json ...]
# Environment: SPP (default 4), SIZE (default 256), DENSITIES, REPEAT (default 3: the median is printed).
set -euo pipefail
cd "$(dirname "$0")/.."
spp="${SPP:-4}"
size="${SIZE:-256}"
repeat="${REPEAT:-3}"
densities="${DENSITIES:-0.5 1 2 4 8 16}"
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=(assets/cornell-box/scene.json assets/bunny-lowres/scene_lowres.json)
  for s in bunny/scene.json sponza/scene.json teapot-in-stadium/scene.json; do
    [ -f "../shared/scenes/$s" ] && scenes+=("../shared/scenes/$s")
  done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf "%-45s %8s %14s %10s %10s\n" scene lambda grid "build_s" "render_s"
for scene in "${scenes[@]}"; do
  for lambda in $densities; do
    times=()
    for ((i = 0; i < repeat; ++i)); do
      log=$(build/kappa render "$scene" --accel grid --grid-density "$lambda" --spp "$spp" --width "$size" \
              --height "$size" --out "$tmp/x.exr" 2>&1)
      times+=("$(sed -n 's/.*threads: \([0-9.]*\) s,.*/\1/p' <<<"$log")")
      grid=$(sed -n 's/^kappa: grid \([0-9x]*\),.*/\1/p' <<<"$log")
      build=$(sed -n 's/.*built in \([0-9.]*\) s/\1/p' <<<"$log")
    done
    median=$(printf "%s\n" "${times[@]}" | sort -g | sed -n "$(((repeat + 1) / 2))p")
    printf "%-45s %8s %14s %10s %10s\n" "$scene" "$lambda" "$grid" "$build" "$median"
  done
done
