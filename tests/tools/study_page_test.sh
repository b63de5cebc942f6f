#!/usr/bin/env bash
# tools/study.sh writes the committed page (docs/) only from a commit: in a
# scratch git repository holding the study's scripts and a committed
# docs/results.md, it refuses a tree with uncommitted changes and a kappa not
# built from HEAD (exit 2, docs/ untouched); with --draft, and from a clean
# tree with HEAD's kappa, it writes the page (a tiny run: no scene, N = 100),
# marked as a draft or not; a tree changed during the run leaves docs/ as it
# was and keeps the raw outputs, from which tools/study_report.py writes the
# page elsewhere, marked "plus uncommitted changes".
# Usage: study_page_test.sh SOURCE_DIR KAPPA
set -euo pipefail
src="$1" kappa="$2"
fail() { echo "study_page_test: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo="$tmp/repo"
mkdir -p "$repo/tools" "$repo/docs"
cp "$src"/tools/*.sh "$src"/tools/*.py "$repo/tools/"  # the study and the generators it runs
echo "the committed page" > "$repo/docs/results.md"
git -C "$repo" init -q
git -C "$repo" -c user.name=t -c user.email=t@t add -A
git -C "$repo" -c user.name=t -c user.email=t@t commit -q -m page
head=$(git -C "$repo" rev-parse --short=12 HEAD)
# A kappa that says it was built from HEAD, and is the real one otherwise.
cat > "$tmp/kappa-head" <<WRAP
#!/usr/bin/env bash
if [ "\${1:-}" = --version ]; then echo "kappa $head"; else exec "$kappa" "\$@"; fi
WRAP
chmod +x "$tmp/kappa-head"
export STUDY_SCENES=none STUDY_NS=100
page_unchanged() { [ "$(cat "$repo/docs/results.md")" = "the committed page" ] || fail "$1: docs/results.md was written"; }
# refused CASE KAPPA WORDS [VAR=VALUE ...]: `study.sh --quick` with that kappa (and environment) exits 2,
# says WORDS and leaves docs/ as it was; what it said is left in $err.
refused() {
  local case="$1" bin="$2" words="$3" code
  shift 3
  set +e
  err=$(env "$@" KAPPA_BIN="$bin" "$repo/tools/study.sh" --quick 2>&1 >/dev/null); code=$?
  set -e
  [ "$code" = 2 ] || fail "$case: exit $code, not 2: $(tail -n 3 <<<"$err")"
  grep -qF -- "$words" <<<"$err" || fail "$case: said '$(tail -n 1 <<<"$err")'"
  page_unchanged "$case"
}

# A changed tracked file: refused before any work.
echo "# changed" >> "$repo/tools/make_scaling_scene.py"
refused "a dirty tree" "$tmp/kappa-head" 'uncommitted changes (1 files, first: tools/make_scaling_scene.py)'

# The same tree with --draft: the page is written, and says it is a draft.
KAPPA_BIN="$tmp/kappa-head" "$repo/tools/study.sh" --quick --draft 2>"$tmp/draft.err" || fail "--draft on a dirty tree failed: $(tail -n 3 "$tmp/draft.err")"
grep -q '^\*\*A draft\*\*' "$repo/docs/results.md" || fail "--draft: the page is not marked as a draft"
grep -q "from commit \`$head\` plus uncommitted changes" "$repo/docs/results.md" || fail "--draft: the header does not name the commit and its changes"
git -C "$repo" checkout -q -- tools docs
git -C "$repo" clean -qfd docs

# A clean tree, but a kappa built from another commit (the real one): refused.
refused "another commit's kappa" "$kappa" "not built from this commit"

# A tree changed during the run (by its first render): docs/ untouched, the raw outputs kept and usable.
cat > "$tmp/kappa-changes" <<WRAP
#!/usr/bin/env bash
if [ "\${1:-}" = --version ]; then echo "kappa $head"; exit 0; fi
[ -e "$tmp/changed" ] || { echo "# changed mid-run" >> "$repo/tools/make_sphere.py"; touch "$tmp/changed"; }
exec "$kappa" "\$@"
WRAP
chmod +x "$tmp/kappa-changes"
mkdir -p "$tmp/work"
refused "a tree changed during the run" "$tmp/kappa-changes" "the tree changed during the run" TMPDIR="$tmp/work"
kept=$(sed -n 's/.*--data \([^ ]*\) --out DIR$/\1/p' <<<"$err")
[ -f "$kept/meta.json" ] || fail "a tree changed during the run: no raw outputs kept at '$kept'"
/usr/bin/python3 "$repo/tools/study_report.py" --data "$kept" --out "$tmp/elsewhere" >/dev/null 2>&1 ||
  fail "the kept raw outputs do not make a page"
grep -q "from commit \`$head\` plus uncommitted changes" "$tmp/elsewhere/results.md" ||
  fail "the page from the kept outputs does not say 'plus uncommitted changes'"
git -C "$repo" checkout -q -- tools

# A clean tree and HEAD's kappa: the committed page, not marked as a draft.
KAPPA_BIN="$tmp/kappa-head" "$repo/tools/study.sh" --quick 2>/dev/null || fail "a clean tree with HEAD's kappa failed"
grep -q "from commit \`$head\`, with" "$repo/docs/results.md" || fail "a clean page does not name its commit alone"
if grep -q 'A draft' "$repo/docs/results.md"; then fail "a clean page is marked as a draft"; fi
echo "study_page_test: ok"
