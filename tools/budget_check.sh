#!/usr/bin/env bash
# The budgets issue's targets, measured (README: a wall-clock check lives
# here, not in the suite). For each scene, at SIZE x SIZE (256) with
# statistics off:
#   relmse    --target-relmse 0.01, RUNS runs with seeds 1..RUNS: the image's
#             true relMSE against a Kappa reference of REF_SPP (16384) spp
#             with seed 1000 (cached in build/references/, with its variance
#             AOV: the reference's own noise is taken out of the relMSE, see
#             tools/relmse.py), the render's own estimate and their ratio, the
#             spp taken and the render time;
#   adaptive  --adaptive --target-relmse E against uniform sampling given the
#             adaptive render's time as --time-budget: the relMSE of each;
#   time      --time-budget 10s: render.time_s, RUNS runs.
#
#   tools/budget_check.sh [relmse|adaptive|time] SCENE.json ...
#
# Prints Markdown rows and `uptime` before and after.
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
size="${SIZE:-256}" runs="${RUNS:-3}" ref_spp="${REF_SPP:-16384}" target="${TARGET:-0.01}"
what="$1"; shift
python=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The relMSE against the reference, less the reference's own share when it has one.
true_relmse() {
  "$python" tools/relmse.py "$1" "$2" | awk '{v = $2; for (i = 1; i < NF; i++) if ($i == "corrected") v = $(i + 1); print v}'
}
field() { "$python" -c "import json,sys; j=json.load(open(sys.argv[1]))['render']; print(j[sys.argv[2]])" "$1" "$2"; }
name_of() { basename "$(dirname "$1")"; }

reference() {  # scene -> path of its cached reference
  local ref="build/references/$(name_of "$1").${size}.${ref_spp}.exr"
  mkdir -p build/references
  if [ ! -f "$ref" ]; then
    echo "making the reference $ref ($ref_spp spp)..." >&2
    "$kappa" render "$1" --width "$size" --height "$size" --spp "$ref_spp" --seed 1000 --stats off --quiet \
      --aov variance --out "$ref"
  fi
  echo "$ref"
}

echo "uptime before: $(uptime)"
for scene in "$@"; do
  name=$(name_of "$scene")
  case "$what" in
    relmse)
      ref=$(reference "$scene")
      echo "| scene | seed | spp | passes | time s | estimate | true relMSE | estimate / true |"
      echo "|---|---:|---:|---:|---:|---:|---:|---:|"
      for ((seed = 1; seed <= runs; seed++)); do
        "$kappa" render "$scene" --width "$size" --height "$size" --target-relmse "$target" --seed "$seed" --stats off \
          --quiet --out "$tmp/x.exr" --report "$tmp/x.json"
        t_relmse=$(true_relmse "$tmp/x.exr" "$ref")
        est=$(field "$tmp/x.json" relmse_estimate)
        printf "| %s | %d | %s | %s | %.2f | %.5f | %.5f | %.3f |\n" "$name" "$seed" "$(field "$tmp/x.json" spp)" \
          "$(field "$tmp/x.json" passes)" "$(field "$tmp/x.json" time_s)" "$est" "$t_relmse" \
          "$("$python" -c "print($est / $t_relmse)")"
      done
      ;;
    adaptive)
      ref=$(reference "$scene")
      echo "| scene | seed | adaptive: spp min/mean/max | time s | relMSE | uniform at that time: spp | time s | relMSE |"
      echo "|---|---:|---|---:|---:|---:|---:|---:|"
      for ((seed = 1; seed <= runs; seed++)); do
        "$kappa" render "$scene" --width "$size" --height "$size" --target-relmse "$target" --adaptive --seed "$seed" \
          --stats off --quiet --out "$tmp/a.exr" --report "$tmp/a.json"
        t=$(field "$tmp/a.json" time_s)
        "$kappa" render "$scene" --width "$size" --height "$size" --time-budget "${t}s" --seed "$seed" --stats off \
          --quiet --out "$tmp/u.exr" --report "$tmp/u.json"
        printf "| %s | %d | %s/%.1f/%s | %.2f | %.5f | %s | %.2f | %.5f |\n" "$name" "$seed" \
          "$(field "$tmp/a.json" spp_min)" "$(field "$tmp/a.json" spp_mean)" "$(field "$tmp/a.json" spp_max)" "$t" \
          "$(true_relmse "$tmp/a.exr" "$ref")" "$(field "$tmp/u.json" spp)" \
          "$(field "$tmp/u.json" time_s)" "$(true_relmse "$tmp/u.exr" "$ref")"
      done
      ;;
    time)
      echo "| scene | run | budget s | render.time_s | spp | passes | time / budget |"
      echo "|---|---:|---:|---:|---:|---:|---:|"
      for ((run = 1; run <= runs; run++)); do
        "$kappa" render "$scene" --width "$size" --height "$size" --time-budget 10s --stats off --quiet \
          --out "$tmp/x.exr" --report "$tmp/x.json"
        t=$(field "$tmp/x.json" time_s)
        printf "| %s | %d | 10 | %.3f | %s | %s | %.3f |\n" "$name" "$run" "$t" "$(field "$tmp/x.json" spp)" \
          "$(field "$tmp/x.json" passes)" "$("$python" -c "print($t / 10)")"
      done
      ;;
    *) echo "budget_check.sh: relmse, adaptive or time" >&2; exit 2 ;;
  esac
done
echo "uptime after: $(uptime)"
