#!/usr/bin/env bash
# The project's one way to compare two binaries or two settings: runs a kappa
# command N times for each side, the sides taking turns (A B, then B A, ...) so
# both see the same drift in machine speed, and prints per figure the median
# and min-max of each side and the median speed ratio B / A, with `uptime`
# before and after.
#
#   tools/ab.sh [-n ROUNDS] [--flags-a "F"] [--flags-b "F"] A B -- SUBCOMMAND ARGS...
#
# A and B are kappa binaries (the same one twice to compare flag sets given by
# --flags-a / --flags-b, which are appended to that side's arguments). The
# figures depend on the subcommand:
#   render  render.time_s from the report (the render passes only; load and
#           build are outside it), and the accelerator's build_s beside it:
#           ab.sh adds --report and compares seconds
#   bench   every accel x rays x threads row's Mrays/s median, from --json
#   other   the wall time of the whole command
# The ratio is always speed B / speed A: above 1, B is faster.
#
# Example (the dispatch issue's protocol):
#   tools/ab.sh build-old/kappa build/kappa -- bench assets/cornell-box/scene.json \
#       --accel grid,embree --threads 1 --repeat 3 --n 262144
set -euo pipefail

rounds=9
flags_a="" flags_b=""
while [ $# -gt 0 ]; do
  case "$1" in
    -n) rounds="$2"; shift 2 ;;
    --flags-a) flags_a="$2"; shift 2 ;;
    --flags-b) flags_b="$2"; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
if [ $# -lt 4 ] || [ "$3" != "--" ]; then
  echo "usage: tools/ab.sh [-n ROUNDS] [--flags-a F] [--flags-b F] A B -- SUBCOMMAND ARGS..." >&2
  exit 2
fi
bin_a="$1" bin_b="$2"
shift 3
for b in "$bin_a" "$bin_b"; do
  [ -x "$b" ] || { echo "ab.sh: '$b' is not an executable" >&2; exit 2; }
done
case "$rounds" in ''|*[!0-9]*|0) echo "ab.sh: -n takes a whole number >= 1" >&2; exit 2 ;; esac
python=/usr/bin/python3
[ -x "$python" ] || python=python3

subcommand="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One run of side $1 (a or b) in round $2; its figures go to $tmp/$1.$2.json.
run_side() {
  local side="$1" round="$2" bin flags
  shift 2
  if [ "$side" = a ]; then bin="$bin_a" flags="$flags_a"; else bin="$bin_b" flags="$flags_b"; fi
  local out="$tmp/$side.$round"
  local extra=()
  case "$subcommand" in
    render) extra=(--report "$out.report.json" --quiet --out "$out.exr") ;;
    bench) extra=(--json "$out.bench.json") ;;
  esac
  local start end
  start=$(date +%s.%N)
  # shellcheck disable=SC2086  # the flag sets are word lists
  "$bin" "$@" $flags "${extra[@]}" >"$out.stdout" 2>"$out.stderr" || {
    echo "ab.sh: side $side failed (round $round): $bin $* $flags" >&2
    cat "$out.stderr" >&2
    exit 1
  }
  end=$(date +%s.%N)
  echo "$start $end" >"$out.wall"
}

echo "ab.sh: A = $bin_a $flags_a"
echo "ab.sh: B = $bin_b $flags_b"
echo "ab.sh: $rounds rounds of: $*"
echo "uptime before: $(uptime)"
for ((r = 1; r <= rounds; r++)); do
  if ((r % 2)); then order="a b"; else order="b a"; fi
  for side in $order; do run_side "$side" "$r" "$@"; done
done
echo "uptime after:  $(uptime)"

"$python" - "$tmp" "$rounds" "$subcommand" <<'EOF'
import json, os, statistics, sys

tmp, rounds, subcommand = sys.argv[1], int(sys.argv[2]), sys.argv[3]

def figures(side, r):
    """{figure name: (value, higher_is_faster)} of one run."""
    base = os.path.join(tmp, f"{side}.{r}")
    if subcommand == "render":
        with open(base + ".report.json") as f:
            report = json.load(f)
        out = {"render.time_s": (report["render"]["time_s"], False)}
        build_s = report.get(report.get("accel", ""), {}).get("build_s")
        if build_s is not None:
            out[report["accel"] + ".build_s"] = (build_s, False)
        return out
    if subcommand == "bench":
        with open(base + ".bench.json") as f:
            rows = json.load(f)["results"]
        return {f"{x['accel']} {x['rays']} {x['threads']}t Mrays/s": (x["mrays_per_s_median"], True) for x in rows}
    with open(base + ".wall") as f:
        start, end = map(float, f.read().split())
    return {"wall s": (end - start, False)}

runs = {side: [figures(side, r) for r in range(1, rounds + 1)] for side in "ab"}
names = list(runs["a"][0].keys())
print(f"\n{'figure':<34} {'A median (min-max)':>28} {'B median (min-max)':>28} {'B/A speed':>10}")
for name in names:
    a = [run[name][0] for run in runs["a"] if name in run]
    b = [run[name][0] for run in runs["b"] if name in run]
    if not a or not b:
        continue
    higher_is_faster = runs["a"][0][name][1]
    ma, mb = statistics.median(a), statistics.median(b)
    ratio = (mb / ma if higher_is_faster else ma / mb) if ma > 0 and mb > 0 else float("nan")
    fmt = lambda v: f"{statistics.median(v):.4g} ({min(v):.4g}-{max(v):.4g})"
    print(f"{name:<34} {fmt(a):>28} {fmt(b):>28} {ratio:>10.3f}")
EOF
