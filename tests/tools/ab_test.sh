#!/usr/bin/env bash
# tools/ab.sh on cheap runs: a render compared on two flag sets (figures from
# the report), a bench (figures from its JSON), and its refusals.
# Usage: ab_test.sh SOURCE_DIR KAPPA
set -euo pipefail
src="$1" kappa="$2"
ab="$src/tools/ab.sh"
scene="$src/assets/cornell-box/scene.json"
fail() { echo "ab_test: $*" >&2; exit 1; }

out=$("$ab" -n 2 --flags-a "--spp 1" --flags-b "--spp 64" "$kappa" "$kappa" -- render "$scene" --width 32 --height 32)
grep -q '^uptime before: ' <<<"$out" || fail "no uptime before: $out"
grep -q '^uptime after: ' <<<"$out" || fail "no uptime after: $out"
line=$(grep '^render.time_s ' <<<"$out") || fail "no render.time_s row: $out"
# 64 spp against 1 spp: B is slower, so its speed ratio is below 1.
ratio=$(awk '{print $NF}' <<<"$line")
awk -v r="$ratio" 'BEGIN { exit !(r > 0 && r < 1) }' || fail "64 spp against 1 spp read as speed ratio $ratio"
# The build is timed apart from the render, and the same in both sides' settings.
grep -q '^grid2.build_s ' <<<"$out" || fail "no grid2.build_s row (the default accelerator's): $out"

out=$("$ab" -n 1 "$kappa" "$kappa" -- bench "$scene" --accel grid,naive --rays camera,shadow --threads 1 --repeat 1 --n 256)
for row in "grid camera 1t Mrays/s" "grid shadow 1t Mrays/s" "naive camera 1t Mrays/s"; do
  grep -q "^$row " <<<"$out" || fail "no '$row' row: $out"
done

if "$ab" "$kappa" -- render "$scene" 2>/dev/null; then fail "a missing B side was accepted"; fi
if "$ab" -n 0 "$kappa" "$kappa" -- render "$scene" 2>/dev/null; then fail "-n 0 was accepted"; fi
if "$ab" -n 1 "$kappa" "$kappa" -- render "$scene" --spp 0 >/dev/null 2>&1; then fail "a failing run was not reported"; fi
echo "ab_test: ok"
