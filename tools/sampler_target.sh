#!/usr/bin/env bash
# The samplers issue's Cornell target: at the render time the starting
# commit's defaults need for 64 spp, the new defaults' relMSE against the same
# reference, median of RUNS rounds. Each round times OLD's default render of
# 64 spp (--stats off) and then runs NEW's kappa converge with --equal-time at
# that very time, so both see the same machine.
#
#   tools/sampler_target.sh OLD_KAPPA NEW_KAPPA REFERENCE.exr [RUNS=3] [SCENE]
#
# REFERENCE: e.g. kappa render SCENE --width 256 --height 256 --spp 16384
# --seed 12345 --sampler sobol --stats off --aov variance. Needs /usr/bin/python3
# with numpy and OpenImageIO (tools/setup.sh) for tools/relmse.py.
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,12p' "$0"; exit 2; }
old=$1 new=$2 ref=$3 runs=${4:-3}
scene=${5:-$(dirname "$0")/../assets/cornell-box/scene.json}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
film=(--width 256 --height 256 --threads 2 --seed 11 --stats off)
echo "uptime before: $(uptime)"
for i in $(seq "$runs"); do
  "$old" render "$scene" "${film[@]}" --spp 64 --out "$tmp/old.exr" --report "$tmp/old.json" -q
  t=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['render']['time_s'])" "$tmp/old.json")
  old_relmse=$(/usr/bin/python3 "$here/relmse.py" "$tmp/old.exr" "$ref" | awk '{print $2}')
  "$new" converge "$scene" "${film[@]}" --reference "$ref" --spp 1,2,4,8,16,32,64,128,256 \
    --equal-time "$t" --json "$tmp/new.json" -q > /dev/null
  new_relmse=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['settings'][0]['relmse_at_equal_time'])" "$tmp/new.json")
  echo "round $i: old 64 spp in $t s, relMSE $old_relmse; new defaults at $t s: relMSE $new_relmse"
  echo "$t $old_relmse $new_relmse" >> "$tmp/rounds"
done
echo "uptime after: $(uptime)"
/usr/bin/python3 - "$tmp/rounds" <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
t, old, new = (statistics.median(c) for c in zip(*rows))
print(f"median: time {t:.4g} s, old relMSE {old:.5g}, new relMSE {new:.5g}, new / old {new / old:.3f} (target <= 0.5)")
PY
