#!/usr/bin/python3
"""Plots kappa sweep's JSON: cost per ray against the grid's cell count N_c,
log-log, one panel per ray class: measured (median, with the min-max of the
timed passes) beside eq 10's and the extended model's predictions from the
same rays' counts, the fastest resolution marked.

    tools/sweep_plot.py SWEEP.json OUT.png
    tools/sweep_plot.py --check     (exit 0 when a plot can be made)

kappa sweep --plot runs it with /usr/bin/python3 (Debian's matplotlib).
Exit 3 when matplotlib is missing (tools/setup.sh installs python3-matplotlib).
"""
import json
import os
import sys

if len(sys.argv) == 2 and sys.argv[1] == "--check":
    pass
elif len(sys.argv) != 3:
    sys.exit(__doc__)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("sweep_plot.py: python3-matplotlib is missing: run tools/setup.sh", file=sys.stderr)
    sys.exit(3)
if sys.argv[1] == "--check":
    sys.exit(0)

with open(sys.argv[1]) as f:
    data = json.load(f)
classes = []
for p in data["points"]:
    if p["class"] not in classes:
        classes.append(p["class"])
if not classes:
    sys.exit("sweep_plot.py: no points to plot")

fig, axes = plt.subplots(1, len(classes), figsize=(4.2 * len(classes), 3.8), squeeze=False)
for ax, name in zip(axes[0], classes):
    pts = sorted((p for p in data["points"] if p["class"] == name), key=lambda p: p["N_c"])
    x = [p["N_c"] for p in pts]
    ns = lambda key: [p[key] * 1e9 for p in pts]
    measured = ns("seconds_per_ray")
    low = [m - v for m, v in zip(measured, ns("seconds_per_ray_min"))]
    high = [v - m for m, v in zip(measured, ns("seconds_per_ray_max"))]
    ax.errorbar(x, measured, yerr=[low, high], fmt="o-", color="black", label="measured", capsize=2)
    ax.plot(x, ns("eq10_s_per_ray"), "s--", color="tab:blue", label="eq 10")
    ax.plot(x, ns("extended_s_per_ray"), "^--", color="tab:orange", label="extended")
    best = min(range(len(pts)), key=lambda i: measured[i])
    ax.plot([x[best]], [measured[best]], "*", color="tab:red", markersize=14, label="fastest")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("N_c (cells)")
    ax.set_ylabel("ns per ray")
    ax.set_title(name)
    ax.grid(True, which="both", alpha=0.3)
axes[0][0].legend(fontsize=8)
fig.suptitle("%s, %d triangles (calibration: %s)" % (os.path.basename(os.path.dirname(data["scene"])) or data["scene"],
                                                     data["N"], data["calibration"]), fontsize=10)
fig.tight_layout()
# kappa writes to a temporary named *.png.tmp...: the format is given, not guessed from the name.
fig.savefig(sys.argv[2], dpi=90, format="png")
