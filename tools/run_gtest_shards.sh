#!/usr/bin/env bash
# Runs GoogleTest executables in shards, each shard one process, two at a
# time, and prints a failing shard's whole log:
#   tools/run_gtest_shards.sh SHARDS FILTER EXE...
# The sanitizer suite (tools/test.sh --sanitize) runs its tests so rather than
# through ctest's one process a test: an instrumented process pays its
# start-up and its leak check at exit once a process (when the tests still
# linked OpenImageIO's 265 libraries that was 1.2 s a process against 0.02 s
# in the normal build, and one process a test was half of the suite's 710 s).
# A leak is still found, at the shard's exit, and a failing test named.
set -euo pipefail
if [ $# -lt 3 ] || ! [[ "$1" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: tools/run_gtest_shards.sh SHARDS FILTER EXE..." >&2
  exit 2
fi
shards="$1" filter="$2"
shift 2
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
jobs=()
for exe in "$@"; do
  for ((i = 0; i < shards; i++)); do jobs+=("$exe $i"); done
done
run_shard() {  # EXE INDEX SHARDS FILTER LOGDIR
  local log="$5/$(basename "$1").$2.log" start=$SECONDS code=0
  GTEST_TOTAL_SHARDS="$3" GTEST_SHARD_INDEX="$2" timeout 1800 "$1" --gtest_filter="$4" >"$log" 2>&1 || code=$?
  local summary
  summary=$(grep -E '^\[  PASSED  \]|^\[  FAILED  \] [0-9]+ test' "$log" | tr '\n' ' ')
  echo "gtest: $(basename "$1") shard $(($2 + 1))/$3: ${summary:-no summary} ($((SECONDS - start)) s, exit $code)"
  if [ "$code" -ne 0 ]; then
    cat "$log"
    return 1
  fi
}
export -f run_shard
printf '%s\n' "${jobs[@]}" |
  xargs -P 2 -L 1 bash -c 'run_shard "$0" "$1" "'"$shards"'" "'"$filter"'" "'"$logs"'"'
