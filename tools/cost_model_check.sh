#!/usr/bin/env bash
# The cost-model issue's target, measured: for each scene and grid density,
# RUNS renders at the scene's own film (`--spp 16 --threads 2`, statistics on)
# with one calibration, and per model (eq 10, extended) the median over the
# runs of predicted_s / measured_s - 1, in total and per ray class of at
# least 1e5 rays. The runs take turns over the (scene, density) pairs, so the
# machine's drift spreads over all of them. `uptime` before and after.
#
#   tools/cost_model_check.sh [--ratios (first)] [-n RUNS] [-d 8,32,128] [-c CAL.json]
#                             [-s SPP] [-f WxH] [SCENE.json ...]
#
# --ratios judges the model on what it is for, choosing: the candidates are
# the grid at each density and grid2, each run renders every candidate in
# turn (so a slow minute falls on all of them), and for every pair (A, B) and
# ray class the error is (predicted_A / predicted_B) / (measured_A /
# measured_B) - 1 of the extended model and of the coherent one, in that run; a pair's error is its
# median over the runs. Per scene and class of at least 1e5 rays it prints
# the median and the worst |error| over the pairs (target: 0.10 and 0.25), in
# a table for grid resolutions, one for grid against grid2 and one for all;
# scenes the calibration measured are marked and left out of the summaries.
#
# Default scenes: every ../shared/scenes/*/scene.json. Default calibration:
# build/kappa_calibration.json (made by `kappa calibrate` if missing). Default
# frame: the scene's own film, 16 spp. Every render walks every shadow ray
# (--occluder-cache off): the rays the model predicts. Prints a Markdown
# table; the reports stay in $KEEP if set.
set -euo pipefail
cd "$(dirname "$0")/.."
kappa="${KAPPA:-build/kappa}"
runs=3 densities=8,32,128 cal=build/kappa_calibration.json spp=16 film=() ratios=0
if [ "${1:-}" = --ratios ]; then ratios=1; shift; fi
while getopts "n:d:c:s:f:" opt; do
  case "$opt" in
    n) runs="$OPTARG" ;;
    d) densities="$OPTARG" ;;
    c) cal="$OPTARG" ;;
    s) spp="$OPTARG" ;;
    f) [[ "$OPTARG" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "cost_model_check: -f takes WxH, not '$OPTARG'" >&2; exit 2; }
       film=(--width "${BASH_REMATCH[1]}" --height "${BASH_REMATCH[2]}") ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  for s in ../shared/scenes/*/scene.json; do [ -f "$s" ] && scenes+=("$s"); done
fi
[ ${#scenes[@]} -gt 0 ] || { echo "cost_model_check: no scenes (../shared/scenes is absent)" >&2; exit 2; }
[ -f "$cal" ] || "$kappa" calibrate --out "$cal" >/dev/null
out="${KEEP:-$(mktemp -d)}"
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
echo "uptime before: $(uptime)"
IFS=, read -r -a dens <<<"$densities"
# Candidates: grid at each density ("grid:8"), and grid2 in --ratios.
candidates=()
for d in "${dens[@]}"; do candidates+=("grid:$d"); done
[ "$ratios" = 0 ] || candidates+=("grid2:")
for ((r = 1; r <= runs; r++)); do
  for s in "${scenes[@]}"; do
    name=$(basename "$(dirname "$s")")
    # As Kappa names the scene (Scene::name), which the calibration's labels begin with.
    [ "$(basename "$s")" = scene.json ] || name="$(basename "$s" .json)"
    for c in "${candidates[@]}"; do
      accel=${c%%:*} d=${c#*:}
      tag=$accel${d:+-$d}
      "$kappa" render "$s" --spp "$spp" "${film[@]}" --threads 2 --accel "$accel" ${d:+--grid-density "$d"} \
        --occluder-cache off --calibration "$cal" --quiet \
        --out "$out/$name.$tag.$r.exr" --report "$out/$name.$tag.$r.json"
    done
  done
done
echo "uptime after:  $(uptime)"
python=/usr/bin/python3
[ -x "$python" ] || python=python3
if [ "$ratios" = 1 ]; then
  "$python" "$(dirname "$0")/cost_model_ratios.py" "$out" "$runs" "$cal"  # not exec: the EXIT trap removes $out
  exit
fi
"$python" - "$out" "$runs" <<'EOF'
import glob, json, os, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
rows = {}
for f in sorted(glob.glob(os.path.join(out, "*.json"))):
    name, tag, run = os.path.basename(f)[:-5].rsplit(".", 2)
    if not tag.startswith("grid-"):
        continue  # a --ratios run's grid2 reports, in a KEEP folder used for both
    rows.setdefault((name, float(tag.split("-")[1])), []).append(json.load(open(f)))
def err(pred, meas):
    return pred / meas - 1 if meas > 0 else float("nan")
print("\n| scene | λ | res | measured s | eq 10 error | extended error | per class (≥1e5 rays): extended error (eq 10) | capped |")
print("|---|---:|---|---:|---:|---:|---|---:|")
worst = {"eq10": 0.0, "extended": 0.0, "class": 0.0}
for (name, density), reports in sorted(rows.items()):
    med = lambda xs: statistics.median(xs)
    c0 = reports[0]["cost"]
    measured = med([r["cost"]["measured_s"] for r in reports])
    e10 = med([r["cost"]["eq10"]["relative_error"] for r in reports])
    ext = med([r["cost"]["extended"]["relative_error"] for r in reports])
    worst["eq10"] = max(worst["eq10"], abs(e10))
    worst["extended"] = max(worst["extended"], abs(ext))
    classes = []
    for cls in c0["per_class"]:
        if reports[0]["rays"][cls]["count"] < 100000:
            continue
        pc = [r["cost"]["per_class"][cls] for r in reports]
        ce = med([err(p["extended_s"], p["measured_s"]) for p in pc])
        c10 = med([err(p["eq10_s"], p["measured_s"]) for p in pc])
        worst["class"] = max(worst["class"], abs(ce))
        classes.append(f"{cls} {ce:+.3f} ({c10:+.3f})")
    res = "x".join(str(v) for v in reports[0]["grid"]["res"])
    capped = sum(r["cost"]["capped_queries"] for r in reports)
    print(f"| {name} | {density:g} | {res} | {measured:.3f} | {e10:+.3f} | {ext:+.3f} | {', '.join(classes)} | {capped} |")
print(f"\nworst |error|, median of {runs} runs: eq 10 {worst['eq10']:.3f}, extended {worst['extended']:.3f} "
      f"(target 0.10), extended per class {worst['class']:.3f} (target 0.15)")
EOF
