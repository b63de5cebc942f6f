#!/usr/bin/env python3
"""Predicts kappa-mpi's speed-up past this machine (issue 48): simulates its
tile scheduler on K ranks with the per-tile costs of a real frame.

    tools/mpi_scaling.py REPORT.json [--ranks 1,2,4,...] [--threads T]
                         [--latency S] [--bandwidth B] [--service S]
                         [--order report|tiles|pilot|slowest]

REPORT.json is a report of `kappa-mpi render ... --report` (any number of
ranks; `mpirun -np 1` is enough): its `mpi.tile_seconds` are each tile's
seconds on the thread that rendered it, summed over the passes. The
simulation replays what renderer/mpi/mpi_frame_split.cpp does, pass by pass
as one pass of those costs:

- rank 0 hands out tiles one at a time (its own threads take
  theirs with no message); another rank keeps one request in flight: when a
  thread of it takes a tile (the answer to the last request, waited for if it
  has not arrived: a round trip, 2 latencies), the next request leaves, to be
  answered while that tile renders; rank 0's coordinator answers one request
  at a time (`--service` seconds each);
- after the pass every other rank sends its tiles' pixels (every channel,
  4 bytes a float) to rank 0, which receives them one rank after another at
  `--bandwidth` bytes a second, each message a latency more.

The tiles go out in the order `--order` names: `tiles` (tile order), `pilot`
(the costliest first by the report's `mpi.tile_predicted`, as kappa-mpi's
first pass does where a pilot ran), `slowest` (the slowest first by the
measured seconds themselves, as its later passes do by the pass before's);
`report` (the default) is the order the report's first pass went in
(`mpi.first_pass_order`).

The frame's time is the last tile's end plus the gather; the speed-up is the
one-rank frame's time over it, with the same threads a rank; the imbalance
the slowest rank's busy time over the ranks' mean. Loading and building,
which every rank does alone, are not in it (the report's render.time_s is
not either). Prints a Markdown table.
"""
import argparse
import heapq
import json
import sys


def floats_per_pixel(report):
    """The film's floats a pixel: RGB and each AOV the render wrote."""
    aov = report.get("render", {}).get("settings", {}).get("aov", "") or ""
    sizes = {"albedo": 3, "normal": 3, "depth": 1, "cost": 2, "variance": 3, "spp": 1}
    return 3 + sum(sizes.get(name, 0) for name in aov.split(",") if name)


def tile_pixels(width, height, size):
    tiles_x = (width + size - 1) // size
    tiles_y = (height + size - 1) // size
    out = []
    for t in range(tiles_x * tiles_y):
        x0, y0 = (t % tiles_x) * size, (t // tiles_x) * size
        out.append((min(x0 + size, width) - x0) * (min(y0 + size, height) - y0))
    return out


def tile_order(mpi, costs, order):
    """The tiles in the order `order` names (see the module's text)."""
    if order == "report":
        order = "pilot" if mpi.get("first_pass_order") == "pilot" else "tiles"
    if order == "tiles":
        return list(range(len(costs)))
    if order == "pilot":
        predicted = mpi.get("tile_predicted")
        if not predicted or len(predicted) != len(costs):
            sys.exit("--order pilot: the report has no mpi.tile_predicted of its tiles (a frame with no pilot)")
        key = predicted
    else:
        key = costs
    return sorted(range(len(costs)), key=lambda t: -key[t])  # stable: ties in tile order


def simulate(costs, pixels, ranks, threads, latency, bandwidth, service, bytes_per_pixel, order=None):
    """(frame seconds, imbalance) of one pass of `costs` on `ranks` x `threads`,
    the tiles handed out in `order` (default tile order)."""
    order = order if order is not None else list(range(len(costs)))
    state = {"next": 0, "coordinator_free": 0.0}

    def take():
        """The next tile to hand out, or None."""
        if state["next"] >= len(order):
            return None
        state["next"] += 1
        return order[state["next"] - 1]

    def ask(leave):
        """A request leaving a rank at `leave`: (tile or None, when its answer arrives)."""
        answered = max(leave + latency, state["coordinator_free"]) + service
        state["coordinator_free"] = answered
        return take(), answered + latency

    pending = [None] * ranks     # a rank's request in flight: (tile, arrival)
    busy = [0.0] * ranks
    sent_pixels = [0] * ranks
    # Events in time order: (time, kind, rank, thread); at one time, the
    # threads' first takes (kind 0), then requests leaving (1), then threads
    # done with a tile (2), as the messages would queue at rank 0.
    events = [(0.0, 0, r, k) for r in range(ranks) for k in range(threads)]
    heapq.heapify(events)
    finish = 0.0
    while events:
        t, kind, r, k = heapq.heappop(events)
        if kind == 1:
            pending[r] = ask(t)
            continue
        if r == 0:  # rank 0's threads take the next tile with no message
            tile, start = take(), t
        else:
            # The answer to the request in flight (the first: asked now),
            # then the next request, answered while this tile renders.
            tile, arrival = pending[r] if pending[r] else ask(t)
            pending[r] = None
            start = max(t, arrival)
            if tile is not None:
                heapq.heappush(events, (start, 1, r, k))
        if tile is None:
            finish = max(finish, start)
            continue
        end = start + costs[tile]
        busy[r] += costs[tile]
        sent_pixels[r] += pixels[tile]
        finish = max(finish, end)
        heapq.heappush(events, (end, 2, r, k))
    # The gather: rank 0 receives the other ranks' pixels one rank after another.
    gather = sum(latency + sent_pixels[r] * bytes_per_pixel / bandwidth for r in range(1, ranks))
    mean = sum(busy) / ranks
    return finish + gather, (max(busy) / mean if mean > 0 else float("nan"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("report")
    parser.add_argument("--ranks", default="1,2,4,8,16,32,64,128,256,512,1024")
    parser.add_argument("--threads", type=int, default=0, help="threads a rank (default: the report's)")
    parser.add_argument("--latency", type=float, default=2e-6, help="seconds a message (default 2e-6, InfiniBand)")
    parser.add_argument("--bandwidth", type=float, default=10e9, help="bytes a second into rank 0 (default 10e9)")
    parser.add_argument("--service", type=float, default=1e-6, help="seconds the coordinator takes a request")
    parser.add_argument("--order", choices=["report", "tiles", "pilot", "slowest"], default="report",
                        help="the order the tiles go out in (default: the report's first pass's)")
    args = parser.parse_args()
    with open(args.report) as f:
        report = json.load(f)
    mpi = report.get("mpi")
    if not mpi or not mpi.get("tile_seconds"):
        sys.exit(f"{args.report}: no mpi.tile_seconds (a report of kappa-mpi render, schema 16 or later)")
    costs = [float(c) for c in mpi["tile_seconds"]]
    threads = args.threads or (mpi["threads_per_rank"] if isinstance(mpi["threads_per_rank"], int) else 1)
    render = report["render"]
    pixels = tile_pixels(render["width"], render["height"], mpi["tile_size"])
    if len(pixels) != len(costs):
        sys.exit(f"{args.report}: {len(costs)} tile costs for a {render['width']}x{render['height']} frame of {len(pixels)} tiles")
    bytes_per_pixel = 4 * floats_per_pixel(report)
    ranks = [int(k) for k in args.ranks.split(",")]
    order = tile_order(mpi, costs, args.order)
    base, _ = simulate(costs, pixels, 1, threads, args.latency, args.bandwidth, args.service, bytes_per_pixel, order)
    print(f"{report.get('scene', '?')}: {render['width']}x{render['height']}, {render['spp']} spp, {len(costs)} tiles "
          f"({sum(costs):.3f} thread-seconds, the largest {max(costs) * 1e3:.2f} ms), {threads} thread(s) a rank, "
          f"latency {args.latency:g} s, bandwidth {args.bandwidth:g} B/s, order {args.order}")
    print()
    print("| ranks | predicted frame s | speed-up | efficiency | imbalance |")
    print("|---:|---:|---:|---:|---:|")
    for k in ranks:
        seconds, imbalance = simulate(costs, pixels, k, threads, args.latency, args.bandwidth, args.service,
                                      bytes_per_pixel, order)
        speedup = base / seconds if seconds > 0 else float("nan")
        print(f"| {k} | {seconds:.4f} | {speedup:.2f} | {speedup / k:.2f} | {imbalance:.2f} |")


if __name__ == "__main__":
    main()
