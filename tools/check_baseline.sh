#!/usr/bin/env bash
# Builds the statistics-free baseline that tools/stats_overhead.sh compares
# against (cmake -DKAPPA_STATS=OFF, in build-nostats/) and checks that it
# traces the same rays as the main build with --stats off, for the same seed,
# and refuses --stats on. Run by tools/test.sh after the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${KAPPA_JOBS:-2}"
if [ ! -f build-nostats/build.ninja ]; then
  cmake -S . -B build-nostats -G Ninja -DCMAKE_BUILD_TYPE=Release -DKAPPA_STATS=OFF >/dev/null
fi
cmake --build build-nostats -j "$jobs" --target kappa
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=assets/cornell-box/scene.json
args=(--spp 2 --width 32 --height 32 --seed 7 -q)
build/kappa render "$scene" "${args[@]}" --stats off --out "$tmp/main.exr" --report "$tmp/main.json"
build-nostats/kappa render "$scene" "${args[@]}" --out "$tmp/base.exr" --report "$tmp/base.json"
rays() { sed -n 's/^ *"rays": \([0-9][0-9]*\),*$/\1/p' "$1" | head -n 1; }
main_rays=$(rays "$tmp/main.json") base_rays=$(rays "$tmp/base.json")
if [ -z "$main_rays" ] || [ "$main_rays" != "$base_rays" ]; then
  echo "check_baseline: the baseline traced '$base_rays' rays, the main build '$main_rays'" >&2
  exit 1
fi
set +e
build-nostats/kappa render "$scene" "${args[@]}" --stats on --out "$tmp/on.exr" 2>"$tmp/err"
code=$?
set -e
if [ "$code" -ne 2 ] || [ -e "$tmp/on.exr" ]; then
  echo "check_baseline: --stats on in the baseline exited $code (expected 2, no image)" >&2
  exit 1
fi
echo "check_baseline: the KAPPA_STATS=OFF build traces the same $main_rays rays and refuses --stats on: $(head -n 1 "$tmp/err")"
