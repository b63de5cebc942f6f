#!/usr/bin/python3
"""Writes the results page from tools/study.sh's raw outputs:

    tools/study_report.py --data WORK --out DIR

WORK holds what study.sh measured (meta.json, scenes.tsv, steps.tsv, sweep/*.json, kappa/*.json,
model/*.json, scaling/FAMILY/N/{auto,model}-{time,count}.json). Writes DIR/results.md, its plots in
DIR/results/*.png and DIR/results/manifest.json (every table's column kinds and every PNG's size in
pixels, for tests/tools/study_quick_test.py), each to a temporary name first and renamed into place.
Every number and every claim of the page's paragraphs is computed here from those outputs; the only
numbers not measured are the paper's predicted exponents, which the page labels as such.
"""
import argparse
import glob
import json
import math
import os
import statistics
import sys

import numpy as np

from study_accels import accels_section, levels_section
from study_ratios import ratios_section
from study_page import (CLASS_COLOURS, DPI, NONE, RENDER_CLASSES, Page, finite, new_figure, num, opt, opt_ratio, pct,
                        ratio, read_json, read_tsv)

# Sweep classes a render casts (lines are the paper's uniform lines, not a render's rays).
RENDER_MIX = ["camera", "bounce", "shadow"]

FAMILIES = {
    "sphere": "tessellated unit sphere (cube sphere, `tools/make_sphere.py`)",
    "soup": "random soup in [-1, 1]³, edge ∝ N^-1/2 (constant total area, `tools/make_soup.py`)",
    "soup-fixed": "random soup in [-1, 1]³, fixed edge 0.2 (`make_soup.py --fixed-edge 0.2`)",
    "sphere-in-box": "sphere of radius 0.05 in an open box of side 20 (10 triangles)",
}
# The paper's exponents of each quantity against N, per family: at a fixed density lambda = N_c / N (what
# auto keeps, while the Theta_tot bound does not lower it) from eqs 10, 21 and 24, and at the optimal N_c
# of Table 2. Derivation (e_L = 0: rays do not shorten as N grows):
#   p_tot ~ N_c^(1/3); Theta_tot = N + D(O) N_c^(1/3) + SA(O) N_c^(2/3) (eq 21, V(O) = 0);
#   tests per ray = p_avg Theta_tot kappa = p_tot Theta_tot kappa / N_c; storage ~ N_c + Theta_tot.
#   sphere, soup, sphere-in-box: D(O) ~ N^(1/2), SA(O) ~ 1 (e_D = 1/2, e_SA = 0): Theta_tot ~ N,
#     case 1 of Table 2: N_c ~ N, E(T) ~ N^(1/3), storage ~ N.
#   soup-fixed: D(O) ~ N, SA(O) ~ N (e_D = 1, e_SA = 1): at fixed lambda Theta_tot ~ N^(5/3), tests ~ N;
#     Table 2's case 9 (on case 13's boundary, where the naive method is as good): N_c ~ 1, E(T) ~ N,
#     storage ~ N.
QUANTITIES = [  # key, label
    ("N_c", "N_c (cells)"),
    ("bytes", "grid bytes"),
    ("theta_tot", "Θ_tot"),
    ("p_tot", "cells per ray (p_tot)"),
    ("p_avg_theta_tot", "p_avg·Θ_tot (tests per ray at κ = 1)"),
    ("kappa", "κ (all rays)"),
    ("tests", "tests per ray (≈ p_avg·Θ_tot·κ)"),
    ("ns_per_ray", "time per ray"),
]
THIRD = 1.0 / 3.0
PAPER = {
    "case1": {"lambda": {"N_c": 1, "bytes": 1, "theta_tot": 1, "p_tot": THIRD, "p_avg_theta_tot": THIRD,
                         "kappa": 0, "tests": THIRD, "ns_per_ray": THIRD},
              "optimal": {"N_c": 1, "bytes": 1, "theta_tot": 1, "p_tot": THIRD, "p_avg_theta_tot": THIRD,
                          "kappa": 0, "tests": THIRD, "ns_per_ray": THIRD}},
    "case9": {"lambda": {"N_c": 1, "bytes": 5 * THIRD, "theta_tot": 5 * THIRD, "p_tot": THIRD,
                         "p_avg_theta_tot": 1, "kappa": 0, "tests": 1, "ns_per_ray": 1},
              "optimal": {"N_c": 0, "bytes": 1, "theta_tot": 1, "p_tot": 0, "p_avg_theta_tot": 1,
                          "kappa": 0, "tests": 1, "ns_per_ray": 1}},
}
PAPER_CASE = {"sphere": "case1", "soup": "case1", "sphere-in-box": "case1", "soup-fixed": "case9"}
EXPONENT_TEXT = {"case1": "e_D = 1/2, e_SA = 0, e_V = 0, e_L = 0: Table 2's case 1",
                 "case9": "e_D = 1, e_SA = 1, e_V = 0, e_L = 0: Table 2's case 9, on the boundary of case 13"}


# ---------------------------------------------------------------------------------------------- formatting

def exponent(x):
    """The paper's exponents as fractions where they are thirds."""
    for text, value in (("0", 0), ("1/3", THIRD), ("2/3", 2 * THIRD), ("1", 1), ("5/3", 5 * THIRD)):
        if abs(x - value) < 1e-9:
            return text
    return num(x)


# ---------------------------------------------------------------------------------------------- reading

def slope(ns, ys):
    """Least-squares slope of log y on log N over the points where both are positive and finite."""
    pts = [(n, y) for n, y in zip(ns, ys) if finite(n) and finite(y) and n > 0 and y > 0]
    if len(pts) < 2 or len({n for n, _ in pts}) < 2:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def median_abs_rel_error(pred, meas):
    errs = [abs(p / m - 1.0) for p, m in zip(pred, meas) if finite(p) and finite(m) and m > 0]
    return statistics.median(errs) if errs else None


# ---------------------------------------------------------------------------------------------- sections

def header(page, meta, scenes, steps):
    page.add("# Kappa: measured results")
    page.add()
    page.para("Written by `%s` (mode: %s) on %s from commit `%s`%s, with `%s`. Every number on this page "
              "was measured by that run or computed from its measurements, except the paper's predicted "
              "exponents in the scaling study, which are labelled as such."
              % (meta["command"], meta["mode"], meta["date"], meta["git"],
                 " plus uncommitted changes" if meta["git_dirty"] else "", meta["kappa_bin"]))
    if meta.get("draft"):
        page.para("**A draft** (`--draft`): not the committed results page, which comes from a clean commit and "
                  "the kappa built from it.")
    if meta.get("restricted"):
        page.para("**A partial run**, restricted by `%s`: not the whole study." % meta["restricted"])
    page.add("- machine: %s, %s cores (`nproc`)" % (meta["cpu"], meta["nproc"]))
    page.add("- `uptime` before: `%s`" % meta["uptime_before"])
    page.add("- `uptime` after: `%s`" % meta["uptime_after"])
    page.add("- total run time: %d s (%.1f min), this page's writing excluded" % (meta["seconds"], meta["seconds"] / 60.0))
    s = meta["settings"]
    page.add("- settings: sweep `%s`; κ renders `%s`; model's choice `%s`; scaling study N = %s, `%s`, at most "
             "%d s a size" % (s["sweep"], s["kappa"], s["model"], ", ".join(str(n) for n in s["scaling_ns"]),
                              s["scaling"], s["size_budget_s"]))
    page.add()
    kinds = {}
    for kind, _, seconds in steps:
        k = kinds.setdefault(kind, [0, 0.0])
        k[0] += 1
        k[1] += float(seconds)
    page.para("Where the time went (wall-clock seconds of each kind of step, from the run's own log):")
    page.table(["step", "runs", "seconds"], ["text", "num", "num"],
               [[k, str(v[0]), num(v[1])] for k, v in kinds.items()])
    skipped = [s for s in scenes if s["status"] != "ok"]
    if skipped:
        page.para("**Skipped scenes** (not on this page): " +
                  "; ".join("%s (%s)" % (s["name"], s["note"]) for s in skipped) + ".")
    fallbacks = [s for s in scenes if s["status"] == "ok" and s["note"]]
    if fallbacks:
        page.para("Scenes read from `assets/` instead: " +
                  "; ".join("%s (%s)" % (s["name"], s["note"]) for s in fallbacks) + ".")


def sweep_section(page, data_dir, scenes, record):
    page.add("## 1. Cost per ray against the grid's resolution (`kappa sweep`)")
    page.add()
    finding_at = len(page.lines)  # the section's finding, once its scenes are read
    page.para("`kappa sweep` builds the grid at resolutions geometric in N_c and, at each, times `kappa "
              "bench`'s ray sets with statistics off (the median of the timed passes) and counts the same "
              "rays' cells and tests, beside two predictions from those counts: the paper's eq 10 (T0 + "
              "p_tot·Ts + p_avg·Θ_tot·κ·Th) and the extended model (per-class constants, occupied cells, "
              "hits, cache misses). λ = N_c / N is the density, cells per triangle. Each plot has one panel "
              "per ray class: measured cost (with the range of the timed passes), both predictions and the "
              "fastest resolution (star).")
    summary = []
    for sc in scenes:
        path = os.path.join(data_dir, "sweep", sc["name"] + ".json")
        if sc["status"] != "ok" or not os.path.exists(path):
            continue
        d = read_json(path)
        n_tri = d["N"]
        classes = list(dict.fromkeys(p["class"] for p in d["points"]))
        page.add("### %s (N = %d triangles)" % (sc["name"], n_tri))
        page.add()
        rows, per_class = [], {}
        for c in classes:
            pts = sorted((p for p in d["points"] if p["class"] == c), key=lambda p: p["N_c"])
            meas = [p["seconds_per_ray"] for p in pts]
            best = min(range(len(pts)), key=lambda i: meas[i])
            info = {"best": pts[best], "points": pts}
            for model, key in (("eq10", "eq10_s_per_ray"), ("extended", "extended_s_per_ray")):
                pred = [p[key] for p in pts]
                ok = all(finite(v) for v in pred)
                info[model] = {
                    "err": median_abs_rel_error(pred, meas) if ok else None,
                    "opt": min(range(len(pts)), key=lambda i: pred[i]) if ok else None,
                }
                o = info[model]["opt"]
                info[model]["loss"] = meas[o] / meas[best] if o is not None else None
            per_class[c] = info
            e, x = info["eq10"], info["extended"]
            rows.append([c, pts[best]["res"], num(pts[best]["N_c"]), num(pts[best]["N_c"] / n_tri),
                         num(meas[best] * 1e9),
                         opt(pts[e["opt"]]["N_c"] / n_tri if e["opt"] is not None else None),
                         opt_ratio(e["loss"]), opt(100 * e["err"] if finite(e["err"]) else None, 2),
                         opt(pts[x["opt"]]["N_c"] / n_tri if x["opt"] is not None else None),
                         opt_ratio(x["loss"]), opt(100 * x["err"] if finite(x["err"]) else None, 2)])
        fig, axes = new_figure("sweep", 1, len(classes))
        for ax, c in zip(axes[0], classes):
            pts = per_class[c]["points"]
            x = [p["N_c"] for p in pts]
            m = [p["seconds_per_ray"] * 1e9 for p in pts]
            lo = [mi - p.get("seconds_per_ray_min", p["seconds_per_ray"]) * 1e9 for mi, p in zip(m, pts)]
            hi = [p.get("seconds_per_ray_max", p["seconds_per_ray"]) * 1e9 - mi for mi, p in zip(m, pts)]
            colour = CLASS_COLOURS.get(c, "black")
            ax.errorbar(x, m, yerr=[lo, hi], fmt="o-", color=colour, capsize=2, label="measured")
            for key, style, label in (("eq10_s_per_ray", "s:", "eq 10"), ("extended_s_per_ray", "^--", "extended")):
                if all(finite(p[key]) for p in pts):
                    ax.plot(x, [p[key] * 1e9 for p in pts], style, color=colour, alpha=0.6, label=label)
            b = per_class[c]["best"]
            ax.plot([b["N_c"]], [b["seconds_per_ray"] * 1e9], "*", color="tab:red", markersize=13, label="fastest")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("N_c (cells)")
            ax.set_title("%s: fastest at λ = %s" % (c, num(per_class[c]["best"]["N_c"] / n_tri)), fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
        axes[0][0].set_ylabel("time per ray (ns)")
        axes[0][0].legend(fontsize=7)
        ext = [per_class[c]["extended"]["err"] for c in classes if finite(per_class[c]["extended"]["err"])]
        fig.suptitle("%s (%d triangles, %d rays per class): the cost per ray varies up to %s× over "
                     "λ = %s–%s%s" % (sc["name"], n_tri, d["n"], flat_factor(per_class, classes),
                                     num(min(p["N_c"] for p in d["points"]) / n_tri),
                                     num(max(p["N_c"] for p in d["points"]) / n_tri),
                                     "; the extended model's median error %s–%s %%" % (pct(min(ext)), pct(max(ext)))
                                     if ext else ""), fontsize=10)
        fig.tight_layout()
        page.figure(fig, "sweep-" + sc["name"], "sweep", "sweep of " + sc["name"])
        lam = [p["N_c"] / n_tri for p in d["points"]]
        text = ("Measured at %d resolutions from λ = %s to %s (N_c %s to %s), %d rays per class, median of %d "
                "passes, %s constants." % (len({p["res"] for p in d["points"]}), num(min(lam)), num(max(lam)),
                                           num(min(p["N_c"] for p in d["points"])),
                                           num(max(p["N_c"] for p in d["points"])), d["n"], d["repeat"],
                                           d["calibration"]))
        if d.get("skipped"):
            text += " %d larger resolution(s) skipped by `--grid-max-bytes`." % len(d["skipped"])
        text += " Fastest λ per class: " + ", ".join(
            "%s %s (%s ns)" % (c, num(per_class[c]["best"]["N_c"] / n_tri),
                               num(per_class[c]["best"]["seconds_per_ray"] * 1e9)) for c in classes) + "."
        errs = {m: [per_class[c][m]["err"] for c in classes if finite(per_class[c][m]["err"])]
                for m in ("eq10", "extended")}
        if errs["eq10"] and errs["extended"]:
            better = sum(1 for c in classes if finite(per_class[c]["extended"]["err"]) and
                         finite(per_class[c]["eq10"]["err"]) and
                         per_class[c]["extended"]["err"] < per_class[c]["eq10"]["err"])
            text += (" The extended model's median |error| is smaller than eq 10's on %d of %d classes "
                     "(over the classes: extended %s–%s %%, eq 10 %s–%s %%)." %
                     (better, len(classes), pct(min(errs["extended"])), pct(max(errs["extended"])),
                      pct(min(errs["eq10"])), pct(max(errs["eq10"]))))
            for m, label in (("eq10", "eq 10's"), ("extended", "the extended model's")):
                losses = [(per_class[c][m]["loss"], c) for c in classes if finite(per_class[c][m]["loss"])]
                if losses:
                    worst = max(losses)
                    text += (" Taking %s predicted optimum costs at most %s %% more than the fastest resolution "
                             "(%s)." % (label, pct(worst[0] - 1), worst[1]))
        page.para(text)
        page.table(["class", "fastest res", "N_c", "λ", "ns/ray", "eq 10 optimum λ", "its cost ÷ fastest",
                    "eq 10 median abs error %", "extended optimum λ", "its cost ÷ fastest",
                    "extended median abs error %"],
                   ["text", "res", "num", "num", "num", "num?", "num?", "num?", "num?", "num?", "num?"], rows)
        record["sweeps"][sc["name"]] = {c: {"fastest_res": per_class[c]["best"]["res"],
                                            "fastest_N_c": per_class[c]["best"]["N_c"],
                                            "fastest_s_per_ray": per_class[c]["best"]["seconds_per_ray"],
                                            "eq10_median_abs_error": per_class[c]["eq10"]["err"],
                                            "extended_median_abs_error": per_class[c]["extended"]["err"]}
                                        for c in classes}
        summary.append((sc, d, per_class))
    if summary:
        page.lines[finding_at:finding_at] = [sweep_finding(summary), ""]
    return summary


def flat_factor(per_class, classes):
    """The largest ratio, over the classes, of the slowest to the fastest swept resolution's cost."""
    f = max(max(p["seconds_per_ray"] for p in per_class[c]["points"]) /
            min(p["seconds_per_ray"] for p in per_class[c]["points"]) for c in classes)
    return num(f, 2)


def sweep_finding(summary):
    """The section's two sentences: where the fastest density lies, and how well each model predicts it."""
    lams, losses = [], []
    for sc, d, per_class in summary:
        for c, info in per_class.items():
            if c in RENDER_MIX:
                lams.append((info["best"]["N_c"] / d["N"], sc["name"], c))
                if finite(info["extended"]["loss"]):
                    losses.append((info["extended"]["loss"], sc["name"], c))
    lo, hi = min(lams), max(lams)
    # Within a factor of 2 of each fastest density (the swept points there), the most any costs more.
    near = []
    for sc, d, per_class in summary:
        for c, info in per_class.items():
            if c not in RENDER_MIX:
                continue
            b = info["best"]
            for p in info["points"]:
                if p is not b and abs(math.log2(p["N_c"] / b["N_c"])) <= 1.01:
                    near.append(p["seconds_per_ray"] / b["seconds_per_ray"])
    text = ("**The fastest density for a render's rays lies between λ = %s (%s, %s) and λ = %s (%s, %s) cells "
            "per triangle" % (num(lo[0]), lo[1], lo[2], num(hi[0]), hi[1], hi[2]))
    text += ("; a swept density within a factor of 2 of a class's fastest costs at most %s %% more.**" %
             pct(max(near) - 1) if near else ".**")
    if losses:
        worst = max(losses)
        text += (" Taking the extended model's predicted optimum instead of the measured one costs at most %s %% "
                 "(%s, %s rays)." % (pct(worst[0] - 1), worst[1], worst[2]))
    return text


def pick_section(page, data_dir, summary):
    """Which resolution a user should pick: the sweep's render-like classes summed, against auto's density and
    --grid-res model's choice, each read at the nearest swept point."""
    page.add("### Which resolution should a user pick?")
    page.add()
    rows, facts = [], []
    for sc, d, per_class in summary:
        classes = [c for c in RENDER_MIX if c in per_class]
        if not classes:
            continue
        n_tri = d["N"]
        by_res = {}
        for c in classes:
            for p in per_class[c]["points"]:
                by_res.setdefault(p["res"], {"N_c": p["N_c"], "s": {}})["s"][c] = p["seconds_per_ray"]
        full = {r: v for r, v in by_res.items() if len(v["s"]) == len(classes)}
        if not full:
            continue
        cost = {r: sum(v["s"].values()) for r, v in full.items()}
        best = min(cost, key=cost.get)
        # The sweep point nearest lambda = 32 (auto's default density) in log distance.
        near = lambda lam: min(full, key=lambda r: abs(math.log(full[r]["N_c"] / n_tri / lam)))
        # auto's density on this scene, from the kappa render (built with --grid-res auto); 32 without it.
        kpath = os.path.join(data_dir, "kappa", sc["name"] + ".json")
        auto_lam = 32.0
        if os.path.exists(kpath):
            kg = read_json(kpath)["grid"]
            auto_lam = kg["N_c"] / kg["N"]
        r32 = near(auto_lam)
        mpath = os.path.join(data_dir, "model", sc["name"] + ".json")
        model_lam = model_ratio = rm = None
        if os.path.exists(mpath):
            m = read_json(mpath)
            model_lam = m["grid"]["N_c"] / m["grid"]["N"]
            rm = near(model_lam)
            model_ratio = cost[rm] / cost[best]
        lams = sorted(v["N_c"] / n_tri for v in full.values())
        step = (lams[-1] / lams[0]) ** (1.0 / (len(lams) - 1)) if len(lams) > 1 else None
        facts.append({"scene": sc["name"], "auto_lam": auto_lam, "best_lam": full[best]["N_c"] / n_tri, "r32_lam": full[r32]["N_c"] / n_tri,
                      "r32": cost[r32] / cost[best], "model_lam": model_lam, "model": model_ratio,
                      "same_point": rm == r32, "step": step})
        rows.append([sc["name"], num(n_tri), best, num(full[best]["N_c"] / n_tri), num(cost[best] * 1e9),
                     num(auto_lam), num(full[r32]["N_c"] / n_tri), ratio(cost[r32] / cost[best]), opt(model_lam),
                     opt_ratio(model_ratio)])
    if not rows:
        page.para("No sweep measured every render-like class, so there is nothing to compare.")
        return
    page.para("Per scene, the cost of one ray of each class a render casts (camera + bounce + shadow, summed "
              "over the sweep's rays) at each swept resolution; the fastest; the swept point nearest the density "
              "`--grid-res auto` built for the κ render below, and its cost against the fastest; and the density "
              "`--grid-res model` chose for a render of the scene (its own pilot and frame), with the "
              "measured cost of the swept point nearest it.")
    page.table(["scene", "N", "fastest res", "λ", "ns (3 rays)", "auto's λ", "nearest point's λ", "its cost ÷ fastest",
                "model's λ", "nearest point's cost ÷ fastest"],
               ["text", "num", "res", "num", "num", "num", "num", "num", "num?", "num?"], rows)
    lams = [f["best_lam"] for f in facts]
    worst32 = max(facts, key=lambda f: f["r32"])
    autos = [f["auto_lam"] for f in facts]
    text = ("The fastest density runs from λ = %s (%s) to λ = %s (%s). `--grid-res auto` (λ = %s here) costs at "
            "most %s %% more than each scene's fastest (on %s)." %
            (num(min(lams)), min(facts, key=lambda f: f["best_lam"])["scene"], num(max(lams)),
             max(facts, key=lambda f: f["best_lam"])["scene"],
             num(min(autos)) if max(autos) < 1.05 * min(autos) else "%s–%s" % (num(min(autos)), num(max(autos))),
             pct(worst32["r32"] - 1), worst32["scene"]))
    steps = [f["step"] for f in facts if f["step"]]
    if steps:
        text += " (The swept points are a factor of about %s apart in λ, so each is read as the nearest.)" % num(
            statistics.median(steps), 2)
    mf = [f for f in facts if finite(f["model"])]
    if mf:
        better = [f for f in mf if not f["same_point"] and f["model"] < f["r32"]]
        same = [f for f in mf if f["same_point"] or f["model"] == f["r32"]]
        worse = [f for f in mf if f not in better and f not in same]
        worstm = max(mf, key=lambda f: f["model"])
        text += (" `--grid-res model`'s choice, read at its nearest swept point, is better than auto's on %d, the "
                 "same on %d and worse on %d of %d scenes, and at most %s %% above the fastest (on %s)." %
                 (len(better), len(same), len(worse), len(mf), pct(worstm["model"] - 1), worstm["scene"]))
        if not worse and better:
            text += " So a user should leave the choice to `--grid-res model`."
        elif not worse:
            text += " The two rules land on the same swept points here, so either will do."
        elif len(better) > len(worse):
            text += (" `--grid-res model` is the better default on most of these scenes, but not on %s."
                     % ", ".join(f["scene"] for f in worse))
        else:
            text += (" `--grid-res auto` is the safer default on these scenes; the model does worse on %s."
                     % ", ".join(f["scene"] for f in worse))
    if worst32["r32"] > 1.1:
        text += (" Where a scene is rendered often, a sweep pays: on %s its fastest resolution is %s %% faster "
                 "than auto's; pass it as `--grid-res NxNxN`." % (worst32["scene"], pct(1 - 1 / worst32["r32"])))
    page.para(text)


def kappa_section(page, data_dir, scenes, record):
    page.add("## 2. κ per ray class")
    page.add()
    rows, rows25, facts, plot = [], [], [], []
    for sc in scenes:
        path = os.path.join(data_dir, "kappa", sc["name"] + ".json")
        if sc["status"] != "ok" or not os.path.exists(path):
            continue
        r = read_json(path)
        g = r["grid"]
        ks = {}
        for c in RENDER_CLASSES + ["all"]:
            v = r["rays"].get(c)
            ks[c] = v["kappa"] if v and v.get("count") and finite(v.get("kappa")) else None
        rows.append([sc["name"], num(g["N"]), "x".join(map(str, g["res"])), num(g["N_c"] / g["N"]),
                     pct(g["empty_fraction"])] + [opt(ks[c]) for c in RENDER_CLASSES + ["all"]])
        plot.append((sc["name"], ks))
        cls = [c for c in RENDER_CLASSES if finite(ks[c])]
        if not cls:
            continue
        top = max(cls, key=lambda c: ks[c])
        v = r["rays"][top]
        rel_p = v["sigma_p"] / v["p_avg"] if finite(v.get("sigma_p")) and finite(v.get("p_avg")) and v["p_avg"] > 0 else None
        rel_t = v["sigma_theta"] / g["theta_avg"] if finite(v.get("sigma_theta")) and g["theta_avg"] > 0 else None
        rows25.append([sc["name"], top, num(v["count"]), num(v["p_tot"]), num(v["tests_per_ray"]), num(v["kappa"]),
                       opt(rel_p), opt(rel_t), opt(v.get("r")), opt(v.get("kappa_eq25"))])
        facts.append({"scene": sc["name"], "k": ks, "top": top, "r": v.get("r"), "rel_p": rel_p, "rel_t": rel_t,
                      "empty": g["empty_fraction"]})
        record["kappa"][sc["name"]] = {"res": g["res"], "N_c": g["N_c"], "kappa": ks}
    if not rows or not facts:
        page.para("No scene was rendered." if not rows else "No class has a finite κ.")
        return facts
    page.para(kappa_finding(facts))
    page.para("`kappa render SCENE --grid-res auto --stats on` (settings in the header): κ (eq 8) of each ray "
              "class over the whole frame, exact from the per-class totals, κ = N_c·Σ p_i Θ_i / (p_tot·Θ_tot). "
              "κ = 1 means a class's rays meet occupied cells as often as uniform lines would; κ > 1, that "
              "they collude with the geometry (visit the crowded cells more), so tests per ray = "
              "p_avg·Θ_tot·κ exceed the uniform estimate by that factor. The empty column is the share of "
              "the grid's cells holding no triangle.")
    page.table(["scene", "N", "res", "λ", "empty %"] + ["κ " + c for c in RENDER_CLASSES] + ["κ all"],
               ["text", "num", "res", "num", "num"] + ["num?"] * (len(RENDER_CLASSES) + 1), rows)
    fig, axes = new_figure("kappa")
    ax = axes[0][0]
    width = 0.8 / len(RENDER_CLASSES)
    for j, c in enumerate(RENDER_CLASSES):
        xs = [i + (j - (len(RENDER_CLASSES) - 1) / 2) * width for i in range(len(plot))]
        ys = [ks[c] if finite(ks[c]) else float("nan") for _, ks in plot]
        ax.bar(xs, ys, width=width, color=CLASS_COLOURS[c], label=c)
    ax.axhline(1.0, color="black", linewidth=1, linestyle="--", label="κ = 1")
    ax.set_yscale("log")
    low = min([ks[c] for _, ks in plot for c in RENDER_CLASSES if finite(ks[c]) and ks[c] > 0] + [1.0])
    ax.set_ylim(bottom=low / 2)
    ax.set_xticks(range(len(plot)))
    ax.set_xticklabels([name for name, _ in plot], fontsize=8, rotation=15)
    ax.set_ylabel("κ (eq 8, dimensionless)")
    ax.set_title(kappa_headline(facts), fontsize=10)
    ax.legend(fontsize=8, ncol=3)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.tight_layout()
    page.figure(fig, "kappa", "kappa", "kappa per ray class and scene")
    # Where kappa > 1, per class, from the table's numbers.
    krows = []
    for c in RENDER_CLASSES:
        ks = [(f["k"][c], f["scene"]) for f in facts if finite(f["k"][c])]
        if not ks:
            continue
        above = [name for k, name in ks if k > 1]
        top = max(ks)
        krows.append([c, str(len(above)), str(len(ks)), num(statistics.median(k for k, _ in ks)), num(top[0]), top[1]])
    page.para("Per class over the scenes: on how many κ > 1, the median κ, and the largest.")
    page.table(["class", "scenes with κ > 1", "scenes", "median κ", "largest κ", "on"],
               ["text", "num", "num", "num", "num", "text"], krows)
    page.para("Why: by the corrected eq 25, κ = 1 + (σ_p/p_avg)(σ_Θ/Θ_avg)·r, so κ is large only where the "
              "occupancy is uneven (σ_Θ/Θ_avg), the class's rays are uneven over the cells (σ_p/p_avg) and the "
              "two are correlated (r). Below, per scene, the class with the largest κ and those factors "
              "(from the per-cell counts, which a large grid samples, so κ_eq25 estimates eq 8's κ; "
              + NONE + " where per-cell counts were not kept).")
    page.table(["scene", "class", "rays", "cells per ray", "tests per ray", "κ", "σ_p/p_avg", "σ_Θ/Θ_avg", "r",
                "κ eq 25"], ["text", "text", "num", "num", "num", "num", "num?", "num?", "num?", "num?"], rows25)
    sents = []
    for f in facts:
        k = f["k"][f["top"]]
        if k > 2 and finite(f["rel_t"]) and finite(f["r"]):
            sents.append("on %s the %s rays (κ = %s) meet a grid whose occupancy is uneven (σ_Θ/Θ_avg = %s, %s %% "
                         "of the cells empty) and visit the crowded cells more (r = %s)" %
                         (f["scene"], f["top"], num(k), num(f["rel_t"]), pct(f["empty"]), num(f["r"])))
        elif k <= 2 and finite(f["rel_t"]):
            sents.append("on %s every class stays at κ ≤ %s (the most: %s), with occupancy σ_Θ/Θ_avg = %s and %s %% "
                         "of the cells empty" % (f["scene"], num(k), f["top"], num(f["rel_t"]), pct(f["empty"])))
    if sents:
        page.para("From the numbers: " + "; ".join(sents) + ".")
    lobe_section(page, data_dir, scenes, record)
    return facts


def kappa_values(facts):
    return [(f["k"][c], f["scene"], c) for f in facts for c in RENDER_CLASSES if finite(f["k"][c])]


def kappa_headline(facts):
    ks = kappa_values(facts)
    top = max(ks)
    small = sum(1 for k, _, _ in ks if k <= 2)
    return ("κ ≤ 2 for %d of %d scene-class pairs; the largest, %s on %s's %s rays" %
            (small, len(ks), num(top[0]), top[1], top[2]))


def kappa_finding(facts):
    """The section's two sentences: is κ O(1) in practice, and where it is not, why (eq 25)."""
    ks = kappa_values(facts)
    small = [k for k in ks if k[0] <= 2]
    big = sorted((k for k in ks if k[0] > 2), reverse=True)
    verdict = ("Yes" if len(small) >= 0.75 * len(ks) else "On some scenes" if len(small) >= 0.25 * len(ks) else "No")
    text = ("**Is κ O(1) in practice? %s: for %d of %d scene-class pairs it is a small constant, κ ≤ 2 (median "
            "over all pairs %s)" % (verdict, len(small), len(ks), num(statistics.median(k for k, _, _ in ks))))
    if big:
        scenes_big = set(name for _, name, _ in big)
        scenes_all = set(name for _, name, _ in ks)
        text += ("; it is not on %d of %d scenes (κ > 2 for some class: the table), up to %s on %s's %s rays.** "
                 "There the grid's occupancy is uneven and the rays visit the crowded cells more than uniform lines "
                 "would: by the corrected eq 25, κ − 1 is the product of the two spreads and their correlation "
                 "(below)." % (len(scenes_big), len(scenes_all), num(big[0][0]), big[0][1], big[0][2]))
    else:
        text += ".** Rays here do not favour the crowded cells enough for eq 25's product of spreads to matter."
    return text


def lobe_section(page, data_dir, scenes, record):
    """κ of the bounce rays by the BSDF lobe that sampled them, on the scenes whose materials have several."""
    rows, facts = [], []
    for sc in scenes:
        path = os.path.join(data_dir, "kappa", sc["name"] + ".json")
        if sc["status"] != "ok" or not os.path.exists(path):
            continue
        lobes = read_json(path)["rays"].get("bounce_by_lobe") or {}
        present = {name: v for name, v in lobes.items() if v and v.get("count")}
        if len(present) < 2:
            continue  # one lobe: its rays are the bounce classes themselves
        for name, v in present.items():
            rows.append([sc["name"], name, num(v["count"]), opt(v.get("cells_per_ray")), opt(v.get("tests_per_ray")),
                         opt(v.get("kappa"))])
            if finite(v.get("kappa")):
                facts.append((v["kappa"], sc["name"], name))
    page.add("### κ per BSDF lobe")
    page.add()
    if not rows:
        page.para("No scene here has bounce rays of more than one lobe.")
        return
    if not facts:
        page.para("No lobe's bounce rays have a finite κ here.")
        return
    by_lobe = {}
    for k, _, lobe in facts:
        by_lobe.setdefault(lobe, []).append(k)
    medians = {lobe: statistics.median(ks) for lobe, ks in by_lobe.items()}
    high, low = max(medians, key=medians.get), min(medians, key=medians.get)
    if len(medians) < 2 or medians[high] == medians[low]:
        page.para("**The bounce rays' κ does not differ by lobe here (median %s).**" % num(medians[high]))
    else:
        page.para("**Bounce rays collude differently by the lobe that sampled them: %s rays have the largest median "
                  "κ (%s), %s the smallest (%s), over the %d scenes with several lobes.** κ per lobe is eq 8 over "
                  "that lobe's rays alone." % (high, num(medians[high]), low, num(medians[low]),
                                               len({s_ for _, s_, _ in facts})))
    page.para("Every bounce ray (bounce1 to bounce3+) counted by the lobe its direction was sampled from "
              "(`rays.bounce_by_lobe`, the κ renders above), on the scenes with more than one lobe.")
    page.table(["scene", "lobe", "rays", "cells per ray", "tests per ray", "κ"],
               ["text", "text", "num", "num?", "num?", "num?"], rows)
    record["kappa_by_lobe"] = [{"scene": s_, "lobe": l, "kappa": k} for k, s_, l in facts]


def scaling_points(data_dir, family):
    pts = []
    for d in sorted(glob.glob(os.path.join(data_dir, "scaling", family, "*")), key=lambda p: int(os.path.basename(p))):
        point = {"n_target": int(os.path.basename(d))}
        for setting in ("auto", "model"):
            t, c = (os.path.join(d, "%s-%s.json" % (setting, k)) for k in ("time", "count"))
            if not (os.path.exists(t) and os.path.exists(c)):
                continue
            tj, cj = read_json(t), read_json(c)
            a = cj["rays"]["all"]
            g = tj["grid"]
            point[setting] = {
                "N": g["N"], "res": g["res"], "N_c": g["N_c"], "bytes": g["bytes"], "theta_tot": g["theta_tot"],
                "build_s": g["build_s"], "rays": tj["render"]["rays"],
                "ns_per_ray": 1e9 * tj["render"]["time_s"] / tj["render"]["rays"],
                "choice_s": tj["grid_choice"]["seconds"] if tj.get("grid_choice") else None,
                # The frame as --grid-res model weighs it: the grid (auto: its build; model: pilot, candidates
                # and build) plus the render, load excluded.
                "frame_s": tj["render"]["time_s"] + (tj["grid_choice"]["seconds"] if tj.get("grid_choice")
                                                     else g["build_s"]),
                "p_tot": a["p_tot"], "p_avg_theta_tot": a["p_avg"] * cj["grid"]["theta_tot"],
                "kappa": a["kappa"], "tests": a["tests_per_ray"], "refs": a["refs_per_ray"],
                "kappa_camera": cj["rays"]["camera"]["kappa"] if cj["rays"].get("camera", {}).get("count") else None,
                "query_ns_per_ray": 1e9 * a["time_s"] / a["count"] if a.get("count") else None,
            }
        pts.append(point)
    return pts


def scaling_section(page, data_dir, meta, record):
    page.add("## 3. The scaling study (the paper's Table 2)")
    page.add()
    finding_at = len(page.lines)
    families = [f for f in meta["settings"]["families"] if os.path.isdir(os.path.join(data_dir, "scaling", f))]
    page.para("Generated scenes (`tools/make_scaling_scene.py`) of N = %s triangles (the real N of each is "
              "in the tables), each rendered at %s with a white sky (so that paths bounce), `%s` at every N: timed "
              "with `--stats off --threads 1` (time per ray = render.time_s / render.rays, whole paths: "
              "traversal and shading, build excluded) and counted with `--stats on` at the very resolution "
              "the timed run built (cells, tests and κ of all rays). Slopes are least-squares fits of log y "
              "on log N over all sizes. The families: %s." %
              (", ".join(str(n) for n in meta["settings"]["scaling_ns"]),
               "`--grid-res auto` (λ %s at the smallest N, the median over the families; lowered where Θ_tot would explode) and "
               "`--grid-res model`" % auto_lambda_text(data_dir, families),
               meta["settings"]["scaling"],
               "; ".join("**%s**: %s" % (f, FAMILIES.get(f, f)) for f in families)))
    page.para("The paper's predictions (κ = O(1), rays that do not shorten with N; exponents for large N, "
              "so at small N the lower-order terms of eq 21 still pull the fits below them): with eq 21 for Θ_tot "
              "(= N + D(O)·N_c^1/3 + SA(O)·N_c^2/3 up to constants), eq 24 for p_tot ∝ N_c^1/3 and eq 10 for "
              "tests per ray = p_avg·Θ_tot·κ, at a fixed density λ and at Table 2's optimal N_c. The sphere, "
              "the constant-area soup and the sphere in the box all have %s (N_c ∝ N, O(N^1/3) per ray, O(N) "
              "storage); the fixed-edge soup has %s: no N_c growth pays, O(N) per ray, as the naive method."
              % (EXPONENT_TEXT["case1"], EXPONENT_TEXT["case9"]))
    skipped = read_tsv(os.path.join(data_dir, "scaling_skipped.tsv"))
    if skipped:
        by = {}
        for fam, n, why in skipped:
            by.setdefault((fam, why), []).append(n)
        page.para("**Sizes not measured**: " + "; ".join(
            "%s at N = %s (%s)" % (fam, ", ".join(ns), why) for (fam, why), ns in by.items()) + ".")
    allpts = {}
    for fam in families:
        pts = scaling_points(data_dir, fam)
        allpts[fam] = pts
        case = PAPER[PAPER_CASE.get(fam, "case1")]
        page.add("### %s" % fam)
        page.add()
        slopes = {}
        for setting in ("auto", "model"):
            sp = [p[setting] for p in pts if setting in p]
            slopes[setting] = {k: slope([q["N"] for q in sp], [q[k] for q in sp]) for k, _ in QUANTITIES}
            # The paper's exponents are asymptotic: the fit over the three largest sizes shows the trend.
            slopes[setting + "-top"] = {k: slope([q["N"] for q in sp[-3:]], [q[k] for q in sp[-3:]])
                                        for k, _ in QUANTITIES} if len(sp) >= 4 else {k: None for k, _ in QUANTITIES}
        rows = [[label, exponent(case["lambda"][k]), exponent(case["optimal"][k]), opt(slopes["auto"][k]),
                 opt(slopes["auto-top"][k]), opt(slopes["model"][k]), opt(slopes["model-top"][k])]
                for k, label in QUANTITIES]
        page.table(["quantity", "paper, λ fixed", "paper, optimal N_c", "auto slope", "auto, 3 largest N",
                    "model slope", "model, 3 largest N"], ["text", "text", "text", "num?", "num?", "num?", "num?"], rows)
        # Per-N values, so that the slopes can be checked by eye.
        vrows = []
        for p in pts:
            for setting in ("auto", "model"):
                if setting not in p:
                    continue
                q = p[setting]
                vrows.append([setting, num(q["N"]), "x".join(map(str, q["res"])), num(q["N_c"] / q["N"]),
                              num(q["bytes"] / 2 ** 20), num(q["p_tot"]), num(q["tests"]), num(q["kappa"]),
                              num(q["ns_per_ray"]), num(q["rays"]),
                              num((q["choice_s"] if finite(q["choice_s"]) else q["build_s"]) * 1e3),
                              num(q["frame_s"] * 1e3)])
        page.table(["grid", "N", "res", "λ", "MiB", "cells per ray", "tests per ray", "κ", "ns per ray", "rays",
                    "build (model: choice) ms", "frame ms"],
                   ["text", "num", "res", "num", "num", "num", "num", "num", "num", "num", "num", "num"], vrows)
        page.para(scaling_text(fam, case, slopes, pts))
        record["scaling"][fam] = {"points": pts, "slopes": slopes}
    fig, axes = new_figure("scaling", 2, 4)
    panels = [("N_c", "N_c", 1), ("bytes", "grid MiB", 2 ** -20), ("p_tot", "cells per ray", 1),
              ("p_avg_theta_tot", "p_avg·Θ_tot", 1), ("kappa", "κ (all rays)", 1), ("tests", "tests per ray", 1),
              ("ns_per_ray", "ns per ray (render)", 1), ("frame_s", "frame s (grid + render)", 1)]
    colours = dict(zip(FAMILIES, ["tab:blue", "tab:orange", "tab:green", "tab:red"]))
    for ax, (key, label, scale) in zip(axes.flat, panels):
        for fam, pts in allpts.items():
            for setting, style in (("auto", "o-"), ("model", "s--")):
                sp = [p[setting] for p in pts if setting in p and finite(p[setting][key]) and p[setting][key] > 0]
                if sp:
                    ax.plot([q["N"] for q in sp], [q[key] * scale for q in sp], style, markersize=3,
                            color=colours.get(fam), label="%s, %s" % (fam, setting))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(label, fontsize=9)
        ax.set_ylabel(label, fontsize=7)
        ax.set_xlabel("N", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="both", alpha=0.3)
    if axes[0][0].get_legend_handles_labels()[0]:
        axes[0][0].legend(fontsize=6)
    fig.suptitle(scaling_headline(record["scaling"]), fontsize=10)
    fig.tight_layout()
    page.figure(fig, "scaling", "scaling", "scaling study")
    page.para("The plot: each quantity against N, log–log, per family (colour), `auto` solid and `model` dashed.")
    finding = scaling_finding(record["scaling"])
    if finding:
        page.lines[finding_at:finding_at] = [finding, ""]
    return record["scaling"]


def scaling_headline(scaling):
    """The scaling figure's title: how cells per ray grow at auto, and where κ grows with N."""
    p = [(v["slopes"]["auto"]["p_tot"], f) for f, v in scaling.items() if finite(v["slopes"]["auto"].get("p_tot"))]
    k = [(v["slopes"]["auto"]["kappa"], f) for f, v in scaling.items() if finite(v["slopes"]["auto"].get("kappa"))]
    if not p:
        return "Against N (triangles): per family, auto solid and model dashed"
    text = "Against N (triangles), at auto: cells per ray grow as N^%s to N^%s (the paper: N^1/3)" % (
        num(min(p)[0], 2), num(max(p)[0], 2))
    moves = ["%s (N^%s)" % (f, num(s_, 2)) for s_, f in k if abs(s_) > 0.1]
    text += ("; κ moves with N on %s" % ", ".join(moves) if moves else
             "; κ stays within N^±0.1 on %s" % ", ".join(f for _, f in k))
    return text + " (model dashed)"


def scaling_finding(scaling):
    """The section's two sentences: the measured exponents of p_tot and Θ_tot against the paper's."""
    parts, kappas = [], []
    for fam, v in scaling.items():
        s = v["slopes"]["auto"]
        if not all(finite(s.get(k)) for k in ("p_tot", "theta_tot", "kappa")):
            continue
        case = PAPER[PAPER_CASE.get(fam, "case1")]["lambda"]
        parts.append("%s N^%s and N^%s (paper N^%s and N^%s)" % (fam, num(s["p_tot"], 2), num(s["theta_tot"], 2),
                                                                  exponent(case["p_tot"]), exponent(case["theta_tot"])))
        kappas.append((s["kappa"], fam))
    if not parts:
        return None
    text = ("**How p_tot and Θ_tot scale (Table 2): at `--grid-res auto`, cells per ray and Θ_tot grow as " +
            "; ".join(parts) + ".**")
    flat = [fam for k, fam in kappas if abs(k) <= 0.1]
    moving = [(k, fam) for k, fam in kappas if abs(k) > 0.1]
    if moving:
        text += (" κ stays O(1) as N grows on %s, but not on %s." %
                 (", ".join(flat) if flat else "no family",
                  ", ".join("%s (κ as N^%s)" % (f, num(k, 2)) for k, f in moving)))
    else:
        text += " κ stays O(1) as N grows on every family (|slope| ≤ 0.1)."
    return text


def auto_lambda_text(data_dir, families):
    lams = []
    for fam in families:
        pts = [p for p in scaling_points(data_dir, fam) if "auto" in p]
        if pts:
            lams.append(pts[0]["auto"]["N_c"] / pts[0]["auto"]["N"])
    return "≈ " + num(statistics.median(lams)) if lams else NONE


def scaling_text(fam, case, slopes, pts):
    """The family's paragraph: the measured slopes against the paper's, and what kappa's slope does."""
    out = []
    for setting in ("auto", "model"):
        s = slopes[setting]
        if not all(finite(s[k]) for k in ("p_tot", "tests", "kappa", "p_avg_theta_tot", "ns_per_ray", "bytes")):
            continue
        t = ("At `%s`, cells per ray grow as N^%s (the paper at fixed λ: N^%s), grid bytes as N^%s (%s), "
             "time per ray as N^%s (%s)." % (setting, num(s["p_tot"], 2), exponent(case["lambda"]["p_tot"]),
                                            num(s["bytes"], 2), "N^" + exponent(case["lambda"]["bytes"]),
                                            num(s["ns_per_ray"], 2), "N^" + exponent(case["lambda"]["ns_per_ray"])))
        t += (" Tests per ray grow as N^%s: p_avg·Θ_tot contributes N^%s and κ N^%s (sum %s)." %
              (num(s["tests"], 2), num(s["p_avg_theta_tot"], 2), num(s["kappa"], 2),
               num(s["p_avg_theta_tot"] + s["kappa"], 2)))
        if s["kappa"] > 0.1:
            ks = [p[setting]["kappa"] for p in pts if setting in p]
            t += " κ is not O(1) here: it rises from %s to %s over the sizes" % (num(ks[0]), num(ks[-1]))
            t += (", and that rise, more than p_avg·Θ_tot's, sets the growth of the tests." if
                  s["kappa"] > s["p_avg_theta_tot"] else ".")
        elif s["kappa"] < -0.1:
            t += " κ falls with N, so the tests grow more slowly than p_avg·Θ_tot."
        else:
            ks = [p[setting]["kappa"] for p in pts if setting in p]
            t += " κ stays within %s–%s, close to the paper's O(1)." % (num(min(ks)), num(max(ks)))
        # p_tot ~ N_c^(1/3) N^(e_L) (eq 24), so the rays' own length in the grid scales as N^(e_L) with:
        e_l = s["p_tot"] - s["N_c"] / 3.0
        if e_l < -0.1:
            t += (" Cells per ray grow as N_c^1/3·N^%s: the rays get shorter as N grows (e_L ≈ %s: they stop at "
                  "nearer hits), where the paper's prediction assumes e_L = 0." % (num(e_l, 2), num(e_l, 2)))
        sp = [p[setting] for p in pts if setting in p]
        t += (" The frame (%s rays at the largest N) spends %s %% of its time on the grid's %s there." %
              (num(sp[-1]["rays"]), pct((sp[-1]["frame_s"] - sp[-1]["ns_per_ray"] * 1e-9 * sp[-1]["rays"]) /
                                        sp[-1]["frame_s"]), "build" if setting == "auto" else "choice and build"))
        out.append(t)
    both = [p for p in pts if "auto" in p and "model" in p]
    if both:
        r = [p["model"]["frame_s"] / p["auto"]["frame_s"] for p in both]
        t = ("`model`'s frame (choice, build and render) takes %s–%s× `auto`'s (build and render) over the sizes."
             % (ratio(min(r)), ratio(max(r))))
        la = both[-1]["auto"]["N_c"] / both[-1]["auto"]["N"]
        lm = both[-1]["model"]["N_c"] / both[-1]["model"]["N"]
        if lm < la / 2:
            t += (" At the largest N it chose λ = %s against `auto`'s %s: it minimises N_r·E(T) + T_build for "
                  "this frame's %s rays, and the fewer the rays, the more the build weighs." %
                  (num(lm), num(la), num(both[-1]["model"]["rays"])))
        elif lm > 2 * la:
            t += " At the largest N it chose a finer grid than `auto`: λ = %s against %s." % (num(lm), num(la))
        else:
            t += " At the largest N its λ = %s is within a factor of 2 of `auto`'s %s." % (num(lm), num(la))
        out.append(t)
    lam = [(p["auto"]["N_c"] / p["auto"]["N"], p["auto"]["N"]) for p in pts if "auto" in p]
    if lam and min(l for l, _ in lam) < 16:
        low = min(lam)
        out.append("`auto` lowered λ to %s at N = %s (the Θ_tot bound)." % (num(low[0]), num(low[1])))
    return " ".join(out) if out else "Too few sizes were measured for slopes."


def findings(kfacts, scaling, afacts, rsum):
    """The page's opening paragraph: the study's three main findings, each from its section's numbers."""
    out = []
    if kfacts:
        ks = kappa_values(kfacts)
        top = max(ks)
        small = sum(1 for k, _, _ in ks if k <= 2)
        f = next(f for f in kfacts if f["scene"] == top[1])
        verdict = ("κ is O(1) in practice" if small >= 0.75 * len(ks) else
                   "κ is O(1) on some scenes and not on others" if small >= 0.25 * len(ks) else
                   "κ is not O(1) in practice")
        why = ""
        if finite(f.get("rel_t")) and finite(f.get("r")) and f["top"] == top[2]:
            why = (", whose grid's occupancy is uneven (σ_Θ/Θ_avg = %s) and whose rays favour the crowded cells "
                   "(r = %s)" % (num(f["rel_t"]), num(f["r"])))
        out.append("**%s**: κ ≤ 2 for %d of %d scene-class pairs (section 2); the largest is %s, on %s's %s rays%s." %
                   (verdict, small, len(ks), num(top[0]), top[1], top[2], why))
    fits = []  # (family, its slopes, the paper's exponents), families with both slopes measured
    for fam, v in (scaling or {}).items():
        sl = v["slopes"]["auto"]
        if all(finite(sl.get(k)) for k in ("p_tot", "theta_tot")):
            fits.append((fam, sl, PAPER[PAPER_CASE.get(fam, "case1")]["lambda"]))
    if fits:
        def holds(key):
            return [f for f in fits if abs(f[1][key] - f[2][key]) <= 0.15]

        def span(fs, key):
            lo, hi = min(f[1][key] for f in fs), max(f[1][key] for f in fs)
            return "N^%s" % num(lo, 2) if num(lo, 2) == num(hi, 2) else "N^%s–%s" % (num(lo, 2), num(hi, 2))

        def growth(f, key):
            return "N^%s against N^%s" % (num(f[1][key], 2), exponent(f[2][key]))

        parts = []
        for key, name in (("p_tot", "p_tot"), ("theta_tot", "Θ_tot")):
            ok = holds(key)
            off = [f for f in fits if f not in ok]
            part = "for %s on %d of %d families" % (name, len(ok), len(fits))
            if len(ok) == 1:
                part += ", %s (%s)" % (ok[0][0], growth(ok[0], key))
            elif ok and len(set(exponent(f[2][key]) for f in ok)) == 1:
                part += ", %s against N^%s" % (span(ok, key), exponent(ok[0][2][key]))
            if off:
                part += ", not on %s" % ", ".join("%s (%s)" % (f[0], growth(f, key)) for f in off)
            parts.append(part)
        text = ("**Table 2's growth (within 0.15 of its exponent) holds %s** (section 3, `--grid-res auto`)" %
                "; ".join(parts))
        out.append(text + ".")
    if afacts:
        worst = max(afacts, key=lambda f: f["grid_over_embree"])
        uneven = [f for f in afacts if finite(f.get("theta_ratio"))]
        most_uneven = max(uneven, key=lambda f: f["theta_ratio"]) if uneven else None
        where = (" (its most uneven grid: Θ_max/Θ_avg = %s)" % num(worst["theta_ratio"])
                 if most_uneven is worst and len(uneven) > 1 else "")
        out.append("**The uniform grid's frames take a median %s× Embree's (a hierarchy's), at most %s× on %s**%s "
                   "(section 5); grid2, which refines the crowded cells, takes %s× Embree's there." %
                   (ratio(statistics.median(f["grid_over_embree"] for f in afacts)), ratio(worst["grid_over_embree"]),
                    worst["scene"], where, ratio(worst["s"]["grid2"] / worst["s"]["embree"])))
    if not out:
        return []
    lines = ["## The findings", "", "%s, each from the measurements below:" %
             {1: "One finding", 2: "Two findings", 3: "Three findings"}[len(out)], ""]
    for i, t in enumerate(out, 1):
        lines += ["%d. %s" % (i, t)]
    lines.append("")
    if rsum:
        title = next(iter(rsum))
        best = max(rsum[title], key=lambda m: rsum[title][m][0])
        lines += ["The cost model, judged on the choices it makes (section 6): the %s model predicts the ratio of "
                  "two grid resolutions' costs within the target on %d of %d scene-class rows." %
                  (best, *rsum[title][best]), ""]
    return lines


# ---------------------------------------------------------------------------------------------- main

def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    data_dir, out_dir = os.path.realpath(a.data), os.path.realpath(a.out)
    # Never over an input: the outputs may not live inside the raw data.
    if out_dir == data_dir or out_dir.startswith(data_dir + os.sep) or data_dir.startswith(out_dir + os.sep + "results"):
        sys.exit("study_report.py: --out must not overlap --data")
    meta = read_json(os.path.join(data_dir, "meta.json"))
    scenes = [{"name": r[0], "path": r[1], "status": r[2], "note": r[3] if len(r) > 3 else ""}
              for r in read_tsv(os.path.join(data_dir, "scenes.tsv"))]
    steps = read_tsv(os.path.join(data_dir, "steps.tsv"))
    os.makedirs(os.path.join(out_dir, "results"), exist_ok=True)
    page = Page(out_dir)
    record = {"meta": meta, "scenes": scenes, "sweeps": {}, "kappa": {}, "scaling": {}}
    try:
        header(page, meta, scenes, steps)
        findings_at = len(page.lines)
        summary = sweep_section(page, data_dir, scenes, record)
        if summary:
            pick_section(page, data_dir, summary)
        kfacts = kappa_section(page, data_dir, scenes, record)
        scaling = scaling_section(page, data_dir, meta, record)
        levels_section(page, data_dir, scenes, record)
        afacts = accels_section(page, data_dir, scenes, record)
        rsum = ratios_section(page, data_dir, meta, record)
        page.lines[findings_at:findings_at] = findings(kfacts, scaling, afacts, rsum)
        staged = list(page.staged)
        for name, obj in (("results/data.json", record),
                          ("results/manifest.json", {"version": 1, "dpi": DPI, "tables": page.tables,
                                                     "pngs": page.pngs})):
            final = os.path.join(out_dir, name)
            tmp = final + ".tmp%d" % os.getpid()
            with open(tmp, "w") as f:
                json.dump(obj, f, indent=1)
                f.write("\n")
            staged.append((tmp, final))
        final = os.path.join(out_dir, "results.md")
        tmp = final + ".tmp%d" % os.getpid()
        with open(tmp, "w") as f:
            f.write("\n".join(page.lines).rstrip() + "\n")
        staged.append((tmp, final))
    except BaseException:
        for tmp, _ in page.staged:
            if os.path.exists(tmp):
                os.remove(tmp)
        raise
    # PNGs a previous page listed that this one does not: remove them (only those the old manifest names).
    old = os.path.join(out_dir, "results", "manifest.json")
    stale = []
    if os.path.exists(old):
        try:
            stale = [p for p in read_json(old).get("pngs", {}) if p not in page.pngs]
        except (ValueError, OSError):
            stale = []
    # The page last, so that it never names a PNG not yet in place.
    for tmp, final in staged:
        os.replace(tmp, final)
    for rel in stale:
        path = os.path.join(out_dir, rel)
        if os.path.isfile(path):
            os.remove(path)


if __name__ == "__main__":
    main()
