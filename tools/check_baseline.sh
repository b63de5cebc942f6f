#!/usr/bin/env bash
# Checks build/kappa-nostats, the statistics-free baseline that
# tools/stats_overhead.sh times `--stats off` against: it is linked from
# kappa's objects with the frame's dispatch compiled without the counting path
# (renderer/CMakeLists.txt), so it must hold none of the render's counting
# frames (render_counting*), refuse `calibrate` (whose measurements they are), trace the same
# rays as kappa with --stats off for the same seed, and refuse --stats on.
# Run by tools/test.sh after the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${KAPPA_JOBS:-2}"
cmake --build build -j "$jobs" --target kappa kappa-nostats
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The counting frames (renderer/render/frames.h): in kappa, not in the baseline.
# (Symbols to files, not piped to grep -q: its early exit would fail the pipe.)
nm -C build/kappa >"$tmp/kappa.nm"
nm -C build/kappa-nostats >"$tmp/nostats.nm"
if ! grep -q 'kappa::render_counting' "$tmp/kappa.nm"; then
  echo "check_baseline: build/kappa has no kappa::render_counting symbol: the check below would prove nothing" >&2
  exit 1
fi
if grep -q 'kappa::render_counting' "$tmp/nostats.nm"; then
  echo "check_baseline: build/kappa-nostats holds a counting frame: $(grep -m 1 'kappa::render_counting' "$tmp/nostats.nm" | cut -c1-160)" >&2
  exit 1
fi
scene=assets/cornell-box/scene.json
args=(--spp 2 --width 32 --height 32 --seed 7 -q)
build/kappa render "$scene" "${args[@]}" --stats off --out "$tmp/main.exr" --report "$tmp/main.json"
build/kappa-nostats render "$scene" "${args[@]}" --out "$tmp/base.exr" --report "$tmp/base.json"
rays() { sed -n 's/^ *"rays": \([0-9][0-9]*\),*$/\1/p' "$1" | head -n 1; }
main_rays=$(rays "$tmp/main.json") base_rays=$(rays "$tmp/base.json")
if [ -z "$main_rays" ] || [ "$main_rays" != "$base_rays" ]; then
  echo "check_baseline: the baseline traced '$base_rays' rays, kappa '$main_rays'" >&2
  exit 1
fi
# The pixels, bit for bit (the files differ in their headers' dates and build times).
same_pixels() {
  /usr/bin/python3 -c '
import sys, numpy as np, OpenImageIO as oiio
a, b = (oiio.ImageBuf(p).get_pixels(oiio.FLOAT) for p in sys.argv[1:3])
sys.exit(0 if a is not None and b is not None and a.shape == b.shape and a.tobytes() == b.tobytes() else 1)' "$1" "$2"
}
if ! same_pixels "$tmp/main.exr" "$tmp/base.exr"; then
  echo "check_baseline: the baseline's image differs from kappa's with --stats off" >&2
  exit 1
fi
set +e
build/kappa-nostats render "$scene" "${args[@]}" --stats on --out "$tmp/on.exr" 2>"$tmp/err"
code=$?
set -e
if [ "$code" -ne 2 ] || [ -e "$tmp/on.exr" ]; then
  echo "check_baseline: --stats on in the baseline exited $code (expected 2, no image)" >&2
  exit 1
fi
set +e
build/kappa-nostats calibrate "$scene" --no-generated --out "$tmp/cal.json" >/dev/null 2>"$tmp/cal.err"
code=$?
set -e
if [ "$code" -ne 2 ] || [ -e "$tmp/cal.json" ]; then
  echo "check_baseline: calibrate in the baseline exited $code (expected 2, no file): $(head -n 1 "$tmp/cal.err")" >&2
  exit 1
fi
echo "check_baseline: kappa-nostats holds no counting frame, refuses calibrate, traces kappa's $main_rays rays to the same image and refuses --stats on: $(head -n 1 "$tmp/err")"
