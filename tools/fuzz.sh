#!/usr/bin/env bash
# Fuzzes one target, or all, with libFuzzer for SECONDS each:
#   tools/fuzz.sh TARGET|all SECONDS
# Targets (tests/fuzz/): obj, mtl, scene_json, gltf, grid_res, exr_reference,
# differential. Builds them with clang, ASan and UBSan in build-fuzz/, seeds
# them from assets/, ../shared/scenes/malformed/ (when it exists) and
# tests/data/fuzz/TARGET/, and keeps the growing corpus in
# build-fuzz/corpus/TARGET/. An input taking over 10 s is a hang. A finding
# (crash, hang, out-of-memory, disagreement) is written under
# build-fuzz/findings/TARGET/ and the script exits 1: make it a regression
# input in tests/data/fuzz/TARGET/ (Fuzz.Replay.TARGET runs it) and fix it.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(obj mtl scene_json gltf grid_res exr_reference differential)
if [ $# -ne 2 ] || ! [[ "$2" =~ ^[0-9]+$ ]] || [ "$2" -lt 1 ]; then
  echo "usage: tools/fuzz.sh TARGET|all SECONDS   (targets: ${targets[*]})" >&2
  exit 2
fi
if [ "$1" = all ]; then
  run=("${targets[@]}")
elif [[ " ${targets[*]} " == *" $1 "* ]]; then
  run=("$1")
else
  echo "fuzz.sh: unknown target '$1' (targets: ${targets[*]}, or all)" >&2
  exit 2
fi
seconds="$2"

tools/setup.sh
if [ ! -f build-fuzz/build.ninja ]; then
  CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKAPPA_DCHECKS=ON \
    -DKAPPA_FUZZ=ON >/dev/null
fi
cmake --build build-fuzz -j "${KAPPA_JOBS:-2}" --target kappa_fuzzers

# Seeds: files whose name fits the target.
seed_pattern() {
  case "$1" in
    obj) echo '*.obj' ;;
    mtl) echo '*.mtl' ;;
    scene_json) echo '*.json' ;;
    gltf) echo '*.gl[tb]*' ;;
    exr_reference) echo '*.exr' ;;
    *) echo '' ;;
  esac
}
max_len() {
  case "$1" in
    grid_res) echo 64 ;;
    differential) echo 4096 ;;
    *) echo 65536 ;;
  esac
}

status=0
for t in "${run[@]}"; do
  corpus="build-fuzz/corpus/$t"
  seeds="build-fuzz/seeds/$t"
  findings="build-fuzz/findings/$t"
  mkdir -p "$corpus" "$findings"
  rm -rf "$seeds" && mkdir -p "$seeds"
  [ -d "tests/data/fuzz/$t" ] && cp tests/data/fuzz/"$t"/* "$seeds"/ 2>/dev/null || true
  pattern="$(seed_pattern "$t")"
  if [ -n "$pattern" ]; then
    for dir in assets ../shared/scenes/malformed; do
      [ -d "$dir" ] || continue
      find "$dir" -name "$pattern" -type f -size -1024k -exec cp -t "$seeds" {} + 2>/dev/null || true
    done
  fi
  dict=()
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  echo "fuzz: $t for ${seconds} s ($(ls "$seeds" | wc -l) seeds, $(ls "$corpus" | wc -l) in the corpus)"
  log="$findings/last_run.log"
  if build-fuzz/fuzz/fuzz_"$t" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
       -max_len="$(max_len "$t")" -artifact_prefix="$findings/" -print_final_stats=1 \
       "$corpus" "$seeds" >"$log" 2>&1; then
    runs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
    echo "fuzz: $t: no finding in $runs runs; corpus $(ls "$corpus" | wc -l) inputs"
  else
    status=1
    echo "fuzz: $t: FINDING, see $log and $findings/:" >&2
    grep -E '^==[0-9]+==ERROR|SUMMARY|Check failed|deadly signal|timeout|out-of-memory' "$log" | head -5 >&2 || true
    ls "$findings" | grep -v last_run.log >&2 || true
  fi
done
exit "$status"
