#!/usr/bin/env bash
# kappa-mpi's speed-up on this machine: renders one frame on 1 rank and on K,
# the two taking turns N times (so both see the machine's drift), and prints
# each side's median render.time_s (the render passes only), its range, and
# the speed-up, with `uptime` before and after. Reports are kept in OUT_DIR
# (tools/mpi_scaling.py reads their mpi.tile_seconds).
#
#   tools/mpi_speedup.sh [-n ROUNDS] [-k RANKS] [-o OUT_DIR] -- RENDER ARGS...
#
# Example (issue 48's note; one thread a rank):
#   tools/mpi_speedup.sh -n 3 -k 2 -- ../shared/scenes/sponza/scene.json --spp 8 --width 512 --height 512 \
#       --stats off --threads 1
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=3 ranks=2 out=""
while [ $# -gt 0 ]; do
  case "$1" in
    -n) rounds="$2"; shift 2 ;;
    -k) ranks="$2"; shift 2 ;;
    -o) out="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "usage: tools/mpi_speedup.sh [-n ROUNDS] [-k RANKS] [-o OUT_DIR] -- RENDER ARGS..." >&2; exit 2 ;;
  esac
done
[ $# -ge 1 ] || { echo "tools/mpi_speedup.sh: no scene" >&2; exit 2; }
[ -x build/kappa-mpi ] || { echo "tools/mpi_speedup.sh: build/kappa-mpi is not built (no MPI found)" >&2; exit 2; }
if [ -z "$out" ]; then out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
mkdir -p "$out"
# Open MPI as root, and where the sandbox refuses its single-copy transport.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
echo "uptime before: $(uptime)"
for ((i = 1; i <= rounds; i++)); do
  for k in 1 "$ranks"; do
    mpirun --oversubscribe -np "$k" build/kappa-mpi render "$@" -q --out "$out/np$k.exr" \
      --report "$out/np$k-$i.json" 2>/dev/null
  done
done
echo "uptime after:  $(uptime)"
/usr/bin/python3 - "$out" "$rounds" "$ranks" <<'PY'
import json, statistics, sys
out, rounds, ranks = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def times(k):
    return [json.load(open(f"{out}/np{k}-{i}.json"))["render"]["time_s"] for i in range(1, rounds + 1)]
one, many = times(1), times(ranks)
last = json.load(open(f"{out}/np{ranks}-{rounds}.json"))["mpi"]
print(f"1 rank:  median {statistics.median(one):.3f} s ({min(one):.3f}-{max(one):.3f})")
print(f"{ranks} ranks: median {statistics.median(many):.3f} s ({min(many):.3f}-{max(many):.3f}), "
      f"imbalance {last['imbalance']:.3f} (last round), tiles per rank {[r['tiles'] for r in last['per_rank']]}")
print(f"speed-up {statistics.median(one) / statistics.median(many):.3f}")
PY
