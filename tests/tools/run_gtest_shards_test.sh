#!/usr/bin/env bash
# tools/run_gtest_shards.sh (the ASan suite's runner) on stand-ins for
# GoogleTest executables: every shard runs once with GoogleTest's shard
# variables and the filter; a failing shard fails the run and shows its log.
# Usage: run_gtest_shards_test.sh SOURCE_DIR
set -euo pipefail
src="$1"
run="$src/tools/run_gtest_shards.sh"
fail() { echo "run_gtest_shards_test: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# A passing stand-in records its shard and arguments.
cat >"$tmp/passing" <<STAND_IN
#!/usr/bin/env bash
echo "\$GTEST_SHARD_INDEX/\$GTEST_TOTAL_SHARDS \$*" >>"$tmp/ran"
echo "[  PASSED  ] 2 tests."
STAND_IN
cat >"$tmp/failing" <<'STAND_IN'
#!/usr/bin/env bash
echo "stand-in: Suite.Case went wrong"
echo "[  FAILED  ] 1 test, listed below:"
exit 1
STAND_IN
chmod +x "$tmp/passing" "$tmp/failing"

out=$("$run" 3 'A.*:-A.Slow' "$tmp/passing") || fail "a passing run failed: $out"
[ "$(sort "$tmp/ran")" = "$(printf '%s\n' "0/3 --gtest_filter=A.*:-A.Slow" "1/3 --gtest_filter=A.*:-A.Slow" \
  "2/3 --gtest_filter=A.*:-A.Slow")" ] || fail "shards ran as: $(cat "$tmp/ran")"
[ "$(grep -c 'shard [123]/3: \[  PASSED  \] 2 tests' <<<"$out")" = 3 ] || fail "no line a shard: $out"

if out=$("$run" 2 '*' "$tmp/passing" "$tmp/failing" 2>&1); then fail "a failing shard was not reported: $out"; fi
grep -q 'stand-in: Suite.Case went wrong' <<<"$out" || fail "the failing shard's log was not shown: $out"

if "$run" 0 '*' "$tmp/passing" 2>/dev/null; then fail "0 shards were accepted"; fi
if "$run" 2 '*' 2>/dev/null; then fail "no executable was accepted"; fi
echo "run_gtest_shards_test: ok"
