#!/usr/bin/env bash
# The model-chooses issue's target for --grid-res model, measured: per scene,
# `kappa render SCENE --spp SPP --stats off` with --grid-res model (its time:
# render.time_s + grid_choice.seconds, the pilot, candidates and build) against
# the same render at each of `kappa sweep`'s resolutions (render.time_s +
# grid.build_s), load excluded. Each sweep resolution is first screened by one
# render at 1 spp; the TOP fastest then take turns with model over RUNS rounds
# at SPP (the first of each round rotating, as tools/ab.sh alternates), and
# the medians are compared. `uptime` before and after.
#
#   tools/grid_model_check.sh [-n RUNS] [-s SPP] [-t TOP] [SCENE.json ...]
#
# Default scenes: every ../shared/scenes/*/scene*.json. Prints a Markdown
# table: the fastest fixed resolution and its median, model's choice and its
# median, and model / fastest (the target: at most 1.05).
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
runs=5 spp=16 top=3
while getopts "n:s:t:" opt; do
  case "$opt" in
    n) runs="$OPTARG" ;;
    s) spp="$OPTARG" ;;
    t) top="$OPTARG" ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  for s in ../shared/scenes/*/scene*.json; do
    case "$s" in */malformed/*) continue ;; esac
    [ -f "$s" ] && scenes+=("$s")
  done
fi
[ ${#scenes[@]} -gt 0 ] || { echo "grid_model_check.sh: no scenes (../shared/scenes is absent)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python=/usr/bin/python3

echo "uptime before: $(uptime)"
echo
echo "| scene | fastest fixed resolution | its median s | model's choice | model median s (choice s) | model / fastest |"
echo "|---|---|---:|---|---:|---:|"
for scene in "${scenes[@]}"; do
  name="$(basename "$(dirname "$scene")")/$(basename "$scene" .json)"
  # The sweep's resolutions (its default range and steps); the rays are few, only the list is used.
  "$kappa" sweep "$scene" --rays camera --n 64 --repeat 1 --json "$tmp/sweep.json" -q
  mapfile -t resolutions < <("$python" -c "
import json, sys
seen = []
for p in json.load(open('$tmp/sweep.json'))['points']:
    if p['res'] not in seen: seen.append(p['res'])
print('\n'.join(seen))")
  # Screening: one render at 1 spp each.
  : > "$tmp/screen.txt"
  for res in "${resolutions[@]}"; do
    "$kappa" render "$scene" --spp 1 --stats off --grid-res "$res" --out "$tmp/x.exr" --report "$tmp/r.json" -q
    "$python" -c "
import json; j = json.load(open('$tmp/r.json'))
print(j['render']['time_s'] + j['grid']['build_s'], '$res')" >> "$tmp/screen.txt"
  done
  mapfile -t finalists < <(sort -g "$tmp/screen.txt" | head -n "$top" | cut -d' ' -f2)
  settings=(model "${finalists[@]}")
  for ((r = 0; r < runs; ++r)); do
    for ((k = 0; k < ${#settings[@]}; ++k)); do
      res="${settings[$(((k + r) % ${#settings[@]}))]}"
      "$kappa" render "$scene" --spp "$spp" --stats off --grid-res "$res" --out "$tmp/x.exr" --report "$tmp/r.json" -q
      "$python" -c "
import json; j = json.load(open('$tmp/r.json'))
g = j['grid_choice']
extra = g['seconds'] if g else j['grid']['build_s']
print('$res', j['render']['time_s'] + extra, g['chosen'] if g else '$res', g['seconds'] if g else 0)" >> "$tmp/runs.txt"
    done
  done
  "$python" - "$tmp/runs.txt" "$name" <<'EOF'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
times, chosen, choice_s = {}, set(), []
for setting, seconds, res, choose in rows:
    times.setdefault(setting, []).append(float(seconds))
    if setting == "model":
        chosen.add(res)
        choice_s.append(float(choose))
medians = {k: statistics.median(v) for k, v in times.items()}
fixed = {k: v for k, v in medians.items() if k != "model"}
best = min(fixed, key=fixed.get)
m = medians["model"]
print("| %s | %s | %.3f | %s | %.3f (%.3f) | %.3f |" % (sys.argv[2], best, fixed[best], "/".join(sorted(chosen)), m,
                                                       statistics.median(choice_s), m / fixed[best]))
EOF
  rm -f "$tmp/runs.txt"
done
echo
echo "uptime after: $(uptime)"
