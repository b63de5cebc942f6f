#!/usr/bin/env python3
"""tools/mpi_scaling.py on frames whose answer is known: equal tiles scale with
the ranks until every tile has its own, one long tile bounds the speed-up, and
a message's latency costs the ranks that must ask for their tiles.
Usage: mpi_scaling_test.py SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile

src = sys.argv[1]


def table(costs, width, height, *flags, predicted=None):
    report = {"scene": "synthetic", "render": {"width": width, "height": height, "spp": 1, "settings": {"aov": ""}},
              "mpi": {"threads_per_rank": 1, "tile_size": 16, "tile_seconds": costs,
                      "first_pass_order": "pilot" if predicted else "tiles", "tile_predicted": predicted}}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "report.json")
        with open(path, "w") as f:
            json.dump(report, f)
        out = subprocess.run([sys.executable, os.path.join(src, "tools", "mpi_scaling.py"), path, *flags],
                             capture_output=True, text=True, check=True).stdout
    rows = {}
    for line in out.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 5 and cells[0].isdigit():
            rows[int(cells[0])] = {"seconds": float(cells[1]), "speedup": float(cells[2]), "imbalance": float(cells[4])}
    return rows


def check(condition, what):
    if not condition:
        sys.exit("mpi_scaling_test: " + what)


free = ["--latency", "0", "--service", "0", "--bandwidth", "1e30"]
# 64 tiles of 10 ms (a 128 x 128 frame), no cost to talk.
even = table([0.01] * 64, 128, 128, "--ranks", "1,2,4,64,128", *free)
for k in (1, 2, 4, 64):
    check(abs(even[k]["speedup"] - k) < 0.005, f"even tiles on {k} ranks: {even[k]}")
    check(abs(even[k]["imbalance"] - 1) < 0.005, f"even tiles on {k} ranks: {even[k]}")
check(abs(even[128]["speedup"] - 64) < 0.005, f"128 ranks for 64 tiles: {even[128]}")
# One tile of 1 s among 63 of 1 ms: no number of ranks beats the long tile.
long_tile = table([1.0] + [0.001] * 63, 128, 128, "--ranks", "1,1024", *free)
check(abs(long_tile[1024]["speedup"] - 1.06) < 0.005 and long_tile[1024]["seconds"] == 1.0, f"one long tile on 1024 ranks: {long_tile[1024]}")
# A 1 ms message each way for tiles of 1 ms: rank 1 spends 3 ms a tile, rank
# 0 one, so two ranks render 4/3 as fast as one, not twice.
slow = table([0.001] * 64, 128, 128, "--ranks", "1,2", "--latency", "0.001", "--service", "0", "--bandwidth", "1e30")
check(1.2 < slow[2]["speedup"] < 1.4, f"latency-bound: {slow[2]}")
# The gather: rank 1's 32 tiles of 256 pixels of RGB (3072 bytes a tile) at
# 1 MB/s, 0.098 s, after 32 ms of rendering.
gathered = table([0.001] * 64, 128, 128, "--ranks", "2", "--latency", "0", "--service", "0", "--bandwidth", "1e6")
check(abs(gathered[2]["seconds"] - 0.1303) < 0.0002, f"the pixels' gather: {gathered[2]}")
# The order: 63 tiles of 1 ms, the last of 1 s. In tile order, on 2 ranks,
# the long tile starts once the short ones are shared out (about 32 ms in);
# the costliest first, it starts at once and the other rank takes the rest.
last_long = [0.001] * 63 + [1.0]
in_order = table(last_long, 128, 128, "--ranks", "2", *free)
check(abs(in_order[2]["seconds"] - 1.032) < 0.002, f"the long tile last, in tile order: {in_order[2]}")
for name, result in (("slowest", table(last_long, 128, 128, "--ranks", "2", "--order", "slowest", *free)),
                     ("pilot", table(last_long, 128, 128, "--ranks", "2", *free, predicted=[1] * 63 + [50])),
                     ("report's pilot", table(last_long, 128, 128, "--ranks", "2", "--order", "pilot", *free,
                                              predicted=[1] * 63 + [50]))):
    check(abs(result[2]["seconds"] - 1.0) < 0.0005, f"the long tile first ({name}): {result[2]}")
print("mpi_scaling_test: ok")
