"""The results page's sections on the hierarchical accelerators (tools/study_report.py): grid2 per level
(its levels' cells, tests and κ for each scene's frame), and the uniform grid against grid2 and Embree,
timed in turns. Every number is read from tools/study.sh's raw outputs: grid2/SCENE.json (a render with
statistics on) and accel/SCENE.ACCEL.ROUND.json (renders with statistics off).
"""
import glob
import os
import statistics

from matplotlib.ticker import ScalarFormatter

from study_page import finite, new_figure, num, opt, pct, ratio, read_json

ACCELS = ["grid", "grid2", "embree"]
ACCEL_COLOURS = {"grid": "tab:blue", "grid2": "tab:orange", "embree": "tab:green"}


def accel_times(data_dir, name):
    """{accel: [render.time_s of each round]} of one scene, the accelerators that ran."""
    out = {}
    for path in glob.glob(os.path.join(data_dir, "accel", "%s.*.*.json" % glob.escape(name))):
        scene, accel, _ = os.path.basename(path)[:-5].rsplit(".", 2)
        if scene == name and accel in ACCELS:
            out.setdefault(accel, []).append(read_json(path)["render"]["time_s"])
    return out


def accels_facts(data_dir, scenes):
    """Per scene: the median seconds of each accelerator, the spread, and the grid's occupancy and κ."""
    facts = []
    for sc in scenes:
        if sc["status"] != "ok":
            continue
        times = accel_times(data_dir, sc["name"])
        if not all(a in times for a in ACCELS):
            continue
        med = {a: statistics.median(times[a]) for a in ACCELS}
        spread = max([max(t) / min(t) - 1 for t in times.values() if min(t) > 0] or [0.0])
        f = {"scene": sc["name"], "s": med, "rounds": min(len(t) for t in times.values()), "spread": spread,
             "grid_over_grid2": med["grid"] / med["grid2"], "grid_over_embree": med["grid"] / med["embree"]}
        kpath = os.path.join(data_dir, "kappa", sc["name"] + ".json")
        if os.path.exists(kpath):
            k = read_json(kpath)
            f["N"] = k["grid"]["N"]
            f["empty"] = k["grid"]["empty_fraction"]
            f["theta_ratio"] = k["grid"]["theta_max"] / k["grid"]["theta_avg"] if k["grid"]["theta_avg"] > 0 else None
            f["tests"] = k["rays"]["all"]["tests_per_ray"]
        gpath = os.path.join(data_dir, "grid2", sc["name"] + ".json")
        if os.path.exists(gpath):
            f["tests_grid2"] = read_json(gpath)["rays"]["all"]["tests_per_ray"]
        facts.append(f)
    return facts


def accels_section(page, data_dir, scenes, record):
    """How much the uniform grid loses against the hierarchical accelerators, and where. Returns the facts
    for the page's findings (empty when nothing was timed)."""
    page.add("## 5. The uniform grid against hierarchical accelerators")
    page.add()
    facts = accels_facts(data_dir, scenes)
    if not facts:
        page.para("No scene was timed with all three accelerators.")
        return facts
    worst = max(facts, key=lambda f: f["grid_over_embree"])
    close = [f for f in facts if f["grid_over_embree"] <= 1.5]
    median_e = statistics.median(f["grid_over_embree"] for f in facts)
    median_2 = statistics.median(f["grid_over_grid2"] for f in facts)
    page.para("**The uniform grid takes a median %s× Embree's time per frame and %s× grid2's; its largest ratio "
              "to Embree's is on %s (%s×)%s.** %s" %
              (ratio(median_e), ratio(median_2), worst["scene"], ratio(worst["grid_over_embree"]),
               ", whose fullest cell holds %s× the mean" % num(worst["theta_ratio"]) if finite(worst.get("theta_ratio"))
               else "",
               ("On %d of %d scenes it is within 1.5× of Embree." % (len(close), len(facts))) if close else
               "On no scene is it within 1.5× of Embree."))
    page.para("Each scene's frame (settings in the header) rendered with `--accel grid` (`--grid-res auto`), "
              "`--accel grid2` (the grid whose crowded cells hold sub-grids) and `--accel embree` "
              "(a BVH, Embree 3) with statistics off, the three taking turns over %d rounds, the first of each "
              "round rotating. Seconds are `render.time_s` (the render passes: traversal and shading), medians "
              "over the rounds; builds are left out (Embree's is not reported). The spread is the largest "
              "max/min − 1 of one accelerator's rounds. Θ_max/Θ_avg is the grid's fullest cell against its "
              "mean (the κ render's grid), tests per ray those of the κ render (grid) and of grid2's render."
              % facts[0]["rounds"])
    rows = []
    for f in facts:
        rows.append([f["scene"], num(f["s"]["grid"]), num(f["s"]["grid2"]), num(f["s"]["embree"]),
                     ratio(f["grid_over_grid2"]), ratio(f["grid_over_embree"]), pct(f["spread"]),
                     opt(f.get("theta_ratio")), opt(f.get("tests")), opt(f.get("tests_grid2"))])
    page.table(["scene", "grid s", "grid2 s", "Embree s", "grid ÷ grid2", "grid ÷ Embree", "spread %",
                "Θ_max/Θ_avg", "tests per ray (grid)", "tests per ray (grid2)"],
               ["text", "num", "num", "num", "num", "num", "num", "num?", "num?", "num?"], rows)
    fig, axes = new_figure("accels")
    ax = axes[0][0]
    width = 0.8 / len(ACCELS)
    for j, a in enumerate(ACCELS):
        xs = [i + (j - (len(ACCELS) - 1) / 2) * width for i in range(len(facts))]
        ax.bar(xs, [f["s"][a] / f["s"]["embree"] for f in facts], width=width, color=ACCEL_COLOURS[a], label=a)
    ax.axhline(1.0, color="black", linewidth=1, linestyle="--")
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(ScalarFormatter())
    ax.set_xticks(range(len(facts)))
    ax.set_xticklabels([f["scene"] for f in facts], fontsize=8, rotation=15)
    ax.set_ylabel("frame time ÷ Embree's (render passes, s/s)")
    ax.set_title("The uniform grid's largest ratio to Embree: %s× on %s (median over scenes %s×)" %
                 (ratio(worst["grid_over_embree"]), worst["scene"], ratio(median_e)), fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.tight_layout()
    page.figure(fig, "accels", "accels", "frame time of grid, grid2 and Embree per scene, relative to Embree")
    uneven = [f for f in facts if finite(f.get("theta_ratio"))]
    if len(uneven) >= 2:
        by_loss = sorted(uneven, key=lambda f: f["grid_over_embree"])
        rho = rank_correlation([f["grid_over_embree"] for f in uneven], [f["theta_ratio"] for f in uneven])
        page.para("Where: least on %s (%s×, Θ_max/Θ_avg = %s), most on %s (%s×, Θ_max/Θ_avg = %s); over the %d "
                  "scenes the rank correlation of the grid's loss with Θ_max/Θ_avg is %s%s." %
                  (by_loss[0]["scene"], ratio(by_loss[0]["grid_over_embree"]), num(by_loss[0]["theta_ratio"]),
                   by_loss[-1]["scene"], ratio(by_loss[-1]["grid_over_embree"]), num(by_loss[-1]["theta_ratio"]),
                   len(uneven), num(rho, 2),
                   " (few scenes: read it as a direction)" if len(uneven) < 5 else ""))
    record["accels"] = facts
    return facts


def rank_correlation(xs, ys):
    """Spearman's rank correlation (ties by order), in [-1, 1]."""
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0] * len(v)
        for k, i in enumerate(order):
            r[i] = k
        return r
    rx, ry = ranks(xs), ranks(ys)
    n = len(xs)
    return 1 - 6 * sum((a - b) ** 2 for a, b in zip(rx, ry)) / (n * (n * n - 1)) if n > 1 else 0.0


def levels_section(page, data_dir, scenes, record):
    """grid2 per level: how its walks divide between the top grid and the sub-grids."""
    page.add("## 4. grid2 per level")
    page.add()
    rows, facts = [], []
    for sc in scenes:
        path = os.path.join(data_dir, "grid2", sc["name"] + ".json")
        if sc["status"] != "ok" or not os.path.exists(path):
            continue
        r = read_json(path)
        g2 = r.get("grid2")
        levels = r["rays"]["all"].get("levels") or []
        if not g2 or not levels:
            continue
        structure = {lv["level"]: lv for lv in g2.get("levels", [])}
        total_tests = sum(lv["tests_per_ray"] for lv in levels if finite(lv.get("tests_per_ray")))
        for lv in levels:
            s = structure.get(lv["level"], {})
            share = lv["tests_per_ray"] / total_tests if total_tests > 0 and finite(lv.get("tests_per_ray")) else None
            rows.append([sc["name"], str(lv["level"]), num(lv["N_c"]), opt(s.get("theta_tot")),
                         opt(lv.get("cells_per_ray")), opt(lv.get("tests_per_ray")), opt(100 * share if finite(share) else None, 2),
                         opt(lv.get("kappa"))])
        sub_tests = sum(lv["tests_per_ray"] for lv in levels if lv["level"] > 0 and finite(lv.get("tests_per_ray")))
        facts.append({"scene": sc["name"], "levels": len(levels), "refined": g2.get("refined"),
                      "sub_test_share": sub_tests / total_tests if total_tests > 0 and len(levels) > 1 else None,
                      "kappa": {lv["level"]: lv.get("kappa") for lv in levels}})
    if not rows:
        page.para("No grid2 render was counted.")
        return facts
    multi = [f for f in facts if f["levels"] > 1]
    if multi:
        shares = [f for f in multi if finite(f["sub_test_share"])]
        top = max(shares, key=lambda f: f["sub_test_share"]) if shares else multi[0]
        low = min(shares, key=lambda f: f["sub_test_share"]) if shares else multi[0]
        kappas = [k for f in multi for lvl, k in f["kappa"].items() if lvl > 0 and finite(k)]
        if not shares or not kappas:
            page.para("**grid2 refined cells on %d of %d scenes.** Its sub-grids' tests or κ were not counted." %
                      (len(multi), len(facts)))
        else:
            page.para("**grid2 refined cells on %d of %d scenes; the tests its sub-grids make are %s–%s %% of all "
                      "(%s to %s).** Within the refined cells the sub-grid levels' κ is %s–%s: the collusion the "
                      "top level sees is measured again inside the crowded cells." %
                      (len(multi), len(facts), pct(low["sub_test_share"]), pct(top["sub_test_share"]), low["scene"],
                       top["scene"], num(min(kappas)), num(max(kappas))))
    else:
        page.para("**grid2 refined no cell on these scenes: its one level is a uniform grid.** Its counts are "
                  "then the grid's at its own density.")
    page.para("`kappa render SCENE --accel grid2 --stats on` (the κ render's settings): per level, its leaves "
              "(N_c), the references they hold (Θ_tot), and per ray of the frame (all classes) the leaves walked, "
              "the triangle tests made there, their share of the tests and κ of that level's leaves (eq 8 over "
              "the level alone).")
    page.table(["scene", "level", "N_c", "Θ_tot", "leaves per ray", "tests per ray", "tests %", "κ"],
               ["text", "num", "num", "num?", "num?", "num?", "num?", "num?"], rows)
    record["grid2_levels"] = facts
    return facts
