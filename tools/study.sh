#!/usr/bin/env bash
# The results page (issue #16): runs the measurements and writes DIR/results.md and its plots in
# DIR/results/ through tools/study_report.py.
#
#   tools/study.sh [--quick] [--draft] [--out DIR]        (DIR defaults to the repo's docs/)
#
# The page in docs/ is the committed one: written there only from a tree without uncommitted changes,
# by a kappa built from that commit (`kappa --version` is HEAD's hash, not "-dirty"), and only if HEAD
# and the tree are the same when the run ends; else the run is refused (exit 2) before it starts, or its
# raw outputs are kept and the page is not written. --draft writes it anyway, marked as a draft at its
# top; --out DIR writes elsewhere, with the commit and "plus uncommitted changes" in its header as ever.
#
# 1. kappa sweep on every scene: cost per ray against the grid's resolution, beside eq 10 and the
#    extended model;
# 2. kappa render with statistics on every scene: kappa per ray class (camera, shadow, bounce1..3+),
#    and --grid-res model's choice;
# 3. the scaling study (the paper's Table 2): generated scenes of 10^2 ... 10^6 triangles (tessellated
#    spheres, constant-area and fixed-edge soups, a small sphere in a large box), each rendered at
#    --grid-res auto and model: timed with --stats off on one thread, counted with --stats on at the same
#    resolution;
# 4. per scene, grid2 with statistics on (its levels), and the uniform grid against the hierarchical
#    accelerators: grid, grid2 and Embree timed with --stats off, taking turns over 3 rounds;
# 5. (full run) the cost model judged on choosing: tools/cost_model_check.sh --ratios on the shared
#    scenes, with a calibration the step makes first, `kappa calibrate --repeat 9` (two calibrations of
#    the default 3 passes, made minutes apart, differed by up to 1.6x in a measurement, and the ratio
#    table they gave by 9 of 22 rows: the results issue's note).
# The full study uses ../shared/scenes (a scene that is missing is skipped, and the page says so); --quick
# uses only assets/ and the scaling study up to 10^4 triangles. The kappa binary is $KAPPA_BIN, else
# build/kappa. Raw outputs stay in a temporary folder, removed at the end unless STUDY_KEEP_WORK=1; the
# page, its PNGs and a manifest of both are written to temporary names and renamed into place by the
# report, so a failed run leaves the previous page whole. To time parts of the full run:
# STUDY_SCENES="dragon sponza" (names as on the page; "none" for no scene) and STUDY_NS="100000 1000000"
# restrict it, and the page says it is partial.
set -euo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
kappa="${KAPPA_BIN:-$repo/build/kappa}"
python=/usr/bin/python3  # Debian's, with numpy and matplotlib (tools/setup.sh)
command_line="tools/study.sh${*:+ $*}"
quick=0
draft=0
out="$repo/docs"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --draft) draft=1 ;;
    --out) [ $# -ge 2 ] || { echo "study.sh: --out needs a folder" >&2; exit 2; }; out="$2"; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "study.sh: unknown argument '$1' (usage: tools/study.sh [--quick] [--draft] [--out DIR])" >&2; exit 2 ;;
  esac
  shift
done
[ -x "$kappa" ] || { echo "study.sh: no kappa binary at $kappa (build it, or set KAPPA_BIN)" >&2; exit 2; }
"$python" -c "import numpy, matplotlib" 2>/dev/null ||
  { echo "study.sh: $python lacks numpy or matplotlib: run tools/setup.sh" >&2; exit 2; }
mkdir -p "$out"
out="$(cd "$out" && pwd)"

# tree_state: HEAD's hash (12 digits) and, after a space, the number of files with uncommitted changes;
# empty outside a git checkout.
tree_state() {
  local head changes
  head=$(git -C "$repo" rev-parse --short=12 HEAD 2>/dev/null) || return 0
  changes=$(git -C "$repo" status --porcelain --untracked-files=no | wc -l)
  echo "$head $changes"
}
state_before="$(tree_state)"
committed_page=0
if [ "$draft" = 0 ] && [ "$(cd "$out" && pwd -P)" = "$(mkdir -p "$repo/docs" && cd "$repo/docs" && pwd -P)" ]; then
  committed_page=1
  refuse() { echo "study.sh: $1: docs/ takes only a page from a commit; pass --draft (the page then says it is a draft) or --out DIR" >&2; exit 2; }
  [ -n "$state_before" ] || refuse "$repo is not a git checkout, so the page's commit is unknown"
  read -r head changes <<< "$state_before"
  if [ "$changes" != 0 ]; then
    refuse "the tree has uncommitted changes ($changes files, first: $(git -C "$repo" status --porcelain --untracked-files=no | head -n 1 | cut -c4-)); commit them"
  fi
  version="$("$kappa" --version 2>/dev/null | head -n 1)" || version="(no --version)"
  [ "$version" = "kappa $head" ] ||
    refuse "$kappa says \"$version\", not \"kappa $head\": it is not built from this commit (tools/build.sh)"
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/kappa-study.XXXXXX")"
# STUDY_KEEP_WORK=1 keeps the raw outputs (to rerun tools/study_report.py --data on them).
if [ "${STUDY_KEEP_WORK:-0}" = 1 ]; then
  trap 'echo "study.sh: raw outputs kept in $work" >&2' EXIT
else
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work/sweep" "$work/kappa" "$work/model" "$work/grid2" "$work/accel" "$work/scaling" "$work/scenes" "$work/img"
start=$(date +%s)
uptime_before="$(uptime)"

# Settings. The full run is sized for 30 minutes on 2 cores (it took 19 on the project's 2-core VM on
# 2026-12-07, 6 of them the ratio check), the quick run for 3 (it took 30 s). The page's header gives the
# measured time of each kind of step.
if [ "$quick" = 1 ]; then
  mode=quick
  sweep_args=(--grid-density 2:512 --steps 5 --n 4096 --repeat 3)
  kappa_args=(--spp 4 --width 128 --height 128)
  model_args=(--spp 4 --width 128 --height 128)
  scaling_ns=(100 316 1000 3162 10000)
  scaling_spp=2
  size_budget=30
else
  mode=full
  sweep_args=(--grid-density 2:512 --steps 9 --n 16384 --repeat 3 --grid-max-bytes 1000000000)
  kappa_args=(--spp 4 --width 256 --height 256)
  model_args=(--spp 4 --width 256 --height 256)
  scaling_ns=(100 316 1000 3162 10000 31623 100000 316228 1000000)
  scaling_spp=4
  size_budget=90
fi
[ -z "${STUDY_NS:-}" ] || read -r -a scaling_ns <<< "$STUDY_NS"
families=(sphere soup soup-fixed sphere-in-box)
# The same frame at every N: the model's choice weighs N_r E(T) against the build, so N_r must not change
# with N.
if [ "$mode" = quick ]; then
  scaling_args=(--width 64 --height 64 --spp "$scaling_spp")
else
  scaling_args=(--width 128 --height 128 --spp "$scaling_spp")
fi

log() { printf '[%4ds] %s\n' "$(($(date +%s) - start))" "$*" >&2; }
# step KIND NAME CMD...: runs CMD and appends its wall time to steps.tsv (the report sums them per kind).
step() {
  local kind="$1" name="$2" t0 t1
  shift 2
  t0=$(date +%s.%N)
  "$@"
  t1=$(date +%s.%N)
  awk -v k="$kind" -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "%s\t%s\t%.3f\n", k, n, b - a }' >> "$work/steps.tsv"
}
: > "$work/steps.tsv"
: > "$work/scenes.tsv"
: > "$work/scaling_skipped.tsv"

# The scenes: NAME PATH [FALLBACK]. The Cornell box and the low-res bunny have unchanged copies in assets/.
shared="$repo/../shared/scenes"
if [ "$mode" = quick ]; then
  scene_list=("cornell-box|$repo/assets/cornell-box/scene.json" "bunny-lowres|$repo/assets/bunny-lowres/scene_lowres.json")
else
  scene_list=(
    "cornell-box|$shared/cornell-box/scene.json|$repo/assets/cornell-box/scene.json"
    "bunny-lowres|$shared/bunny/scene_lowres.json|$repo/assets/bunny-lowres/scene_lowres.json"
    "material-box|$repo/assets/material-box/scene.json"
    "veach-mis|$repo/assets/veach-mis/scene.json"
    "teapot-in-stadium|$shared/teapot-in-stadium/scene.json"
    "sponza|$shared/sponza/scene.json"
    "bunny|$shared/bunny/scene.json"
    "armadillo|$shared/armadillo/scene.json"
    "lucy|$shared/lucy/scene.json"
    "dragon-res2|$shared/dragon/scene_res2.json"
    "dragon|$shared/dragon/scene.json"
    "sponza-textured|$work/scenes/sponza-textured/scene.json"
  )
  # The textured Sponza (its colour maps, cut-out banners and sky image), generated from the shared one.
  if [ -f "$shared/sponza/sponza.obj" ] && { [ -z "${STUDY_SCENES:-}" ] || [[ " $STUDY_SCENES " == *" sponza-textured "* ]]; }; then
    [ -f "$repo/assets/sky/sky.hdr" ] || "$python" "$repo/assets/sky/gen.py" >/dev/null
    step generate sponza-textured "$python" "$repo/tools/scenes/textured_sponza.py" --sponza "$shared/sponza" \
      --out "$work/scenes/sponza-textured" >/dev/null
  fi
fi
rounds=3  # of the accelerators' timed renders
[ "$mode" = full ] || rounds=2

log "study ($mode) into $out; kappa: $kappa; raw outputs in $work"
for entry in "${scene_list[@]}"; do
  IFS='|' read -r name path fallback <<< "$entry"
  if [ -n "${STUDY_SCENES:-}" ] && [[ " $STUDY_SCENES " != *" $name "* ]]; then
    printf '%s\t%s\tskipped\tnot in STUDY_SCENES\n' "$name" "$path" >> "$work/scenes.tsv"
    continue
  fi
  note=""
  shown="${path#"$repo"/}"  # as the page shows it: ../shared/scenes/... or assets/...
  if [ ! -f "$path" ] && [ -n "${fallback:-}" ] && [ -f "$fallback" ]; then
    note="$shown is missing: used the copy in assets/"
    path="$fallback"
  fi
  if [ ! -f "$path" ]; then
    log "SKIPPED $name: $shown is missing (the shared scenes are not beside this clone)"
    printf '%s\t%s\tskipped\t%s is missing\n' "$name" "$path" "$shown" >> "$work/scenes.tsv"
    continue
  fi
  printf '%s\t%s\tok\t%s\n' "$name" "$path" "$note" >> "$work/scenes.tsv"
  log "sweep $name"
  step sweep "$name" "$kappa" sweep "$path" "${sweep_args[@]}" --json "$work/sweep/$name.json" -q
  # kappa per class at --grid-res auto (the grid kappa is reported for); every class's totals are exact.
  # Every render here walks every shadow ray (--occluder-cache off): the
  # paper's rays, and the rays the cost model predicts.
  log "kappa per class: $name"
  step kappa "$name" "$kappa" render "$path" --accel grid --occluder-cache off --grid-res auto --stats on "${kappa_args[@]}" \
    --report "$work/kappa/$name.json" --out "$work/img/$name.exr" -q
  # --grid-res model's choice for the same frame: which resolution it would give a user.
  log "model's choice: $name"
  step model "$name" "$kappa" render "$path" --accel grid --occluder-cache off --grid-res model --stats off "${model_args[@]}" \
    --report "$work/model/$name.json" --out "$work/img/$name-model.exr" -q
  # grid2, counted: its levels' cells, tests and kappa for the same frame.
  log "grid2 per level: $name"
  step grid2 "$name" "$kappa" render "$path" --accel grid2 --occluder-cache off --stats on "${kappa_args[@]}" \
    --report "$work/grid2/$name.json" --out "$work/img/$name-grid2.exr" -q
  # The uniform grid against the hierarchical ones, timed: statistics off, the frame's defaults (the
  # occluder cache on), the three taking turns, the first of each round rotating.
  log "grid, grid2 and Embree timed: $name"
  accels=(grid grid2 embree)
  for ((round = 1; round <= rounds; round++)); do
    for ((k = 0; k < 3; k++)); do
      accel="${accels[$(((round + k) % 3))]}"
      step accel "$name-$accel" "$kappa" render "$path" --accel "$accel" --stats off "${kappa_args[@]}" \
        --report "$work/accel/$name.$accel.$round.json" --out "$work/img/x.exr" -q
    done
  done
done

# res_of REPORT: the resolution a report's grid was built at, as NxNxN.
res_of() { "$python" -c "import json, sys; print('x'.join(map(str, json.load(open(sys.argv[1]))['grid']['res'])))" "$1"; }
# count_limit REPORT: --grid-max-bytes for the counting run: the timed grid, 8 bytes a cell more (room
# for any cell arrays) and 16 MiB. Per-cell counters (about 60 bytes a cell) then fit only small grids; larger ones keep
# exact per-class totals (kappa by eq 8, cells and tests per ray), without per-cell arrays that cost
# seconds per run on grids of 10^7 cells and are not used here.
count_limit() {
  "$python" -c "import json, sys; g = json.load(open(sys.argv[1]))['grid']; print(g['bytes'] + 8 * g['N_c'] + (16 << 20))" "$1"
}

for family in "${families[@]}"; do
  over=""  # set once the next size is predicted over the budget: the family's larger sizes are skipped
  for n in "${scaling_ns[@]}"; do
    if [ -n "$over" ]; then
      log "scaling: $family, N = $n SKIPPED ($over)"
      printf '%s\t%s\t%s\n' "$family" "$n" "$over" >> "$work/scaling_skipped.tsv"
      continue
    fi
    t_size=$(date +%s)
    dir="$work/scenes/$family-$n"
    log "scaling: $family, N = $n"
    step generate "$family-$n" "$python" "$repo/tools/make_scaling_scene.py" "$family" "$n" "$dir"
    res_dir="$work/scaling/$family/$n"
    mkdir -p "$res_dir"
    for setting in auto model; do
      # Timed: statistics off, one thread, so that times compare across settings and N.
      step "scaling-$setting" "$family-$n-time" "$kappa" render "$dir/scene.json" --accel grid --occluder-cache off --grid-res "$setting" \
        --stats off --threads 1 "${scaling_args[@]}" --report "$res_dir/$setting-time.json" --out "$work/img/x.exr" -q
      # Counted: statistics on, at the very resolution the timed run built.
      res="$(res_of "$res_dir/$setting-time.json")"
      step "scaling-$setting" "$family-$n-count" "$kappa" render "$dir/scene.json" --accel grid --occluder-cache off --grid-res "$res" \
        --stats on "${scaling_args[@]}" --grid-max-bytes "$(count_limit "$res_dir/$setting-time.json")" \
        --report "$res_dir/$setting-count.json" --out "$work/img/x.exr" -q
    done
    rm -rf "$dir"  # a 10^6-triangle OBJ is 50-70 MB; keep /tmp small
    took=$(($(date +%s) - t_size))
    # The next size's time, predicted linear in N (load, build and, where kappa grows as for the sphere in
    # the box, the cost per ray): past the budget, the family's larger sizes are skipped.
    prev_n=$n prev_took=$took
    over=""
    for m in "${scaling_ns[@]}"; do
      if [ "$m" -gt "$prev_n" ]; then
        predicted=$(((prev_took * m + prev_n - 1) / prev_n))
        [ "$predicted" -le "$size_budget" ] ||
          over="N = $prev_n took $prev_took s, so N = $m would take about $predicted s, over the budget of $size_budget s a size"
        break
      fi
    done
  done
done

# The cost model on choosing (full run, the shared scenes): the reports stay in $work/ratios.
if [ "$mode" = full ] && [ -z "${STUDY_SCENES:-}" ] && compgen -G "$shared/*/scene.json" >/dev/null; then
  log "the cost model's ratios (tools/cost_model_check.sh --ratios)"
  step ratios-calibration "kappa calibrate" "$kappa" calibrate --repeat 9 --out "$work/calibration.json" \
    > "$work/calibration.log"
  ratio_args=(--ratios -n 3 -s 4 -f 256x256 -c "$work/calibration.json")
  echo "kappa calibrate --repeat 9; tools/cost_model_check.sh ${ratio_args[*]:0:7}" > "$work/ratios.args"
  # A failure (say, a grid over the memory limit) costs the page its section 6, not the whole run.
  step ratios "cost_model_check" env KAPPA="$kappa" KEEP="$work/ratios" "$repo/tools/cost_model_check.sh" \
    "${ratio_args[@]}" > "$work/ratios.md" || { log "the ratios step failed: the page leaves section 6 out"; rm -rf "$work/ratios"; }
fi

end=$(date +%s)
state_after="$(tree_state)"
# The header's facts, passed through the environment so that no quoting in them can break the script.
META_MODE="$mode" META_DRAFT="$draft" META_STATE="$state_before" META_STATE_AFTER="$state_after" META_COMMAND="$command_line" META_OUT="$out" META_UPTIME_BEFORE="$uptime_before" \
META_SECONDS="$((end - start))" META_KAPPA="$kappa" META_SWEEP="${sweep_args[*]}" \
META_KAPPA_ARGS="${kappa_args[*]}" META_MODEL_ARGS="${model_args[*]}" META_NS="${scaling_ns[*]}" \
META_SPP="$scaling_spp" META_FAMILIES="${families[*]}" META_SCALING_ARGS="${scaling_args[*]}" \
META_SIZE_BUDGET="$size_budget" META_RESTRICTED="${STUDY_SCENES:+STUDY_SCENES=\"$STUDY_SCENES\" }${STUDY_NS:+STUDY_NS=\"$STUDY_NS\"}" \
"$python" - "$work/meta.json" "$repo" <<'EOF'
import json, os, subprocess, sys
e = os.environ
def sh(*cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, cwd=sys.argv[2]).stdout.strip()
    except OSError:
        return ""
cpu = [l.split(":", 1)[1].strip() for l in sh("lscpu").splitlines() if l.startswith("Model name:")]
meta = {
    "mode": e["META_MODE"], "command": e["META_COMMAND"], "out": e["META_OUT"],
    "restricted": e["META_RESTRICTED"].strip(),
    "date": sh("date", "-u", "+%Y-%m-%d %H:%M UTC"),
    "draft": e["META_DRAFT"] == "1",
    # The tree as the run began (a committed page's is checked unchanged at its end).
    "git": e["META_STATE"].split()[0] if e["META_STATE"] else "unknown",
    # A tree that changed during the run counts as uncommitted changes.
    "git_dirty": (e["META_STATE"].split()[1] != "0" or e["META_STATE_AFTER"] != e["META_STATE"])
    if e["META_STATE"] else False,
    "nproc": sh("nproc"), "cpu": cpu[0] if cpu else "unknown",
    "uptime_before": e["META_UPTIME_BEFORE"], "uptime_after": sh("uptime"),
    "seconds": int(e["META_SECONDS"]),
    "kappa_bin": os.path.relpath(e["META_KAPPA"], sys.argv[2])
    if e["META_KAPPA"].startswith(sys.argv[2] + os.sep) else e["META_KAPPA"],
    "settings": {"sweep": e["META_SWEEP"], "kappa": e["META_KAPPA_ARGS"], "model": e["META_MODEL_ARGS"],
                 "scaling_ns": [int(n) for n in e["META_NS"].split()], "scaling_spp": int(e["META_SPP"]),
                 "scaling": e["META_SCALING_ARGS"], "size_budget_s": int(e["META_SIZE_BUDGET"]),
                 "families": e["META_FAMILIES"].split()},
}
with open(sys.argv[1], "w") as f:
    json.dump(meta, f, indent=1)
EOF
if [ "$committed_page" = 1 ] && [ "$state_after" != "$state_before" ]; then
  trap - EXIT  # the raw outputs, meta.json included, are kept for tools/study_report.py --data
  echo "study.sh: the tree changed during the run (HEAD and changed files were \"$state_before\", now \"$state_after\"): docs/ is left as it was; write the page elsewhere, marked \"plus uncommitted changes\", with: $python tools/study_report.py --data $work --out DIR" >&2
  exit 2
fi
log "report"
"$python" "$repo/tools/study_report.py" --data "$work" --out "$out"
log "done: $out/results.md ($(($(date +%s) - start)) s)"
