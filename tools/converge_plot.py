#!/usr/bin/python3
"""Plots kappa converge's JSON: relMSE against render time, log-log, one curve
per setting, with the reference's own noise as a dashed floor when known.

    tools/converge_plot.py CONVERGE.json OUT.png
    tools/converge_plot.py --check     (exit 0 when a plot can be made)

kappa converge --plot runs it with /usr/bin/python3 (Debian's matplotlib).
Exit 3 when matplotlib is missing (tools/setup.sh installs python3-matplotlib).
"""
import json
import os
import sys

if len(sys.argv) == 2 and sys.argv[1] == "--check":
    pass  # kappa converge asks, before it renders, whether a plot can be made
elif len(sys.argv) != 3:
    sys.exit(__doc__)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("converge_plot.py: python3-matplotlib is missing: run tools/setup.sh", file=sys.stderr)
    sys.exit(3)
if sys.argv[1] == "--check":
    sys.exit(0)

with open(sys.argv[1]) as f:
    data = json.load(f)

fig, ax = plt.subplots(figsize=(8.5, 5), dpi=120)
# One line style per option varied, one colour per curve: a dozen curves stay
# apart where matplotlib's ten colours would repeat.
styles = ["-", "--", "-.", ":"]
keys = []
colours = plt.get_cmap("tab20").colors
for i, setting in enumerate(data["settings"]):
    key = setting.get("key") or ""
    if key not in keys:
        keys.append(key)
    points = setting["points"]
    times = [p["time_s"] for p in points]
    errors = [p["relmse"] for p in points]
    line, = ax.loglog(times, errors, marker="o", markersize=3, label=setting["name"],
                      linestyle=styles[keys.index(key) % len(styles)], color=colours[i % len(colours)])
    # The last point's samples per pixel, to read cost per sample off the plot.
    ax.annotate(f'{points[-1]["spp"]} spp', (times[-1], errors[-1]), textcoords="offset points", xytext=(4, 2),
                fontsize=7, color=line.get_color())
floor = data["reference"].get("relmse_floor")
if floor:
    ax.axhline(floor, color="grey", linestyle="--", linewidth=0.8, label="reference's own noise")
if data.get("equal_time_s"):
    ax.axvline(data["equal_time_s"], color="grey", linestyle=":", linewidth=0.8, label="equal time (ranking)")
reference = "self-made reference" if data["reference"]["self_made"] else "reference " + os.path.basename(
    data["reference"]["path"])
ax.set_title(f'{data["scene_name"]} {data["width"]}x{data["height"]}, {data["threads"]} threads, '
             f'{reference}', fontsize=9)
ax.set_xlabel("render time (s)")
ax.set_ylabel("relMSE  (mean of (x - ref)² / (ref² + 0.01))")
ax.grid(True, which="both", linewidth=0.3)
ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
fig.tight_layout()
fig.savefig(sys.argv[2], format="png")
