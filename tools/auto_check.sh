#!/usr/bin/env bash
# --accel auto's choice against what each exact accelerator takes, measured:
# per scene, `kappa render SCENE --spp SPP --width W --height W --stats off`
# with --accel auto (its time: render.time_s + accel_choice.seconds, the
# pilot, every candidate's build and the predictions) and with each
# candidate (render.time_s + build_s), load excluded, taking turns over RUNS
# rounds (the first of each round rotating, as tools/ab.sh alternates);
# medians compared. naive is run only on scenes of at most NAIVE_MAX
# triangles (its predicted cost elsewhere is hours). `uptime` before and after.
#
#   tools/auto_check.sh [-n RUNS] [-s SPP] [-w WIDTH] [SCENE.json ...]
#
# Default scenes: every ../shared/scenes/*/scene*.json. Prints a Markdown
# table: per accelerator its median seconds, auto's choice and median, and
# auto / fastest (the target: at most 1.05).
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
runs=3 spp=16 width=256 naive_max="${NAIVE_MAX:-5000}"
while getopts "n:s:w:" opt; do
  case "$opt" in
    n) runs="$OPTARG" ;;
    s) spp="$OPTARG" ;;
    w) width="$OPTARG" ;;
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
[ ${#scenes[@]} -gt 0 ] || { echo "auto_check.sh: no scenes (../shared/scenes is absent)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python=/usr/bin/python3

# Seconds of one render: its passes, and the build of what ran or, for auto,
# its whole choice (the pilot, every candidate's build and prediction).
seconds() {
  "$python" -c "
import json; j = json.load(open('$1'))
build = 0.0
for key in ('grid', 'grid2'):
    if isinstance(j.get(key), dict): build = j[key].get('build_s') or 0.0
if isinstance(j.get('accel_choice'), dict): build = j['accel_choice']['seconds']
print(j['render']['time_s'] + build, j['accel'])"
}
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

echo "uptime before: $(uptime)"
echo
echo "| scene | naive s | grid s | grid2 s | auto's choice | auto s | auto / fastest |"
echo "|---|---:|---:|---:|---|---:|---:|"
for scene in "${scenes[@]}"; do
  name="$(basename "$(dirname "$scene")")/$(basename "$scene" .json)"
  "$kappa" cast "$scene" --rays lines --n 16 --report "$tmp/size.json" -q >/dev/null
  triangles=$("$python" -c "import json; print(json.load(open('$tmp/size.json'))['grid']['N'])")
  accels=(auto grid grid2)
  [ "$triangles" -le "$naive_max" ] && accels+=(naive)
  for a in auto naive grid grid2; do : > "$tmp/$a.txt"; done
  for ((round = 0; round < runs; ++round)); do
    for ((i = 0; i < ${#accels[@]}; ++i)); do
      a="${accels[$(((i + round) % ${#accels[@]}))]}"
      "$kappa" render "$scene" --accel "$a" --spp "$spp" --width "$width" --height "$width" --stats off \
        --out "$tmp/x.exr" --report "$tmp/r.json" -q
      seconds "$tmp/r.json" >> "$tmp/$a.txt"
    done
  done
  row="| $name"
  best=""
  for a in naive grid grid2; do
    if [ -s "$tmp/$a.txt" ]; then
      m=$(cut -d' ' -f1 "$tmp/$a.txt" | median)
      row+=" | $(printf '%.3f' "$m")"
      best=$("$python" -c "print(min(x for x in [$m, ${best:-float('inf')}]))")
    else
      row+=" | not run"
    fi
  done
  chosen=$(cut -d' ' -f2 "$tmp/auto.txt" | sort | uniq -c | sort -rn | awk '{print $2}' | paste -sd/)
  m=$(cut -d' ' -f1 "$tmp/auto.txt" | median)
  row+=" | $chosen | $(printf '%.3f' "$m") | $("$python" -c "print('%.2f' % ($m / $best))") |"
  echo "$row"
done
echo
echo "uptime after: $(uptime)"
