"""The results page's section on the cost model judged on choosing (tools/study_report.py): from the reports
tools/cost_model_check.sh --ratios kept in the study's ratios/ folder, per scene and ray class the median
and worst |error| of the predicted ratio of two candidates' costs against the ratio measured in the same run,
for the extended and the coherent model, through tools/cost_model_ratios.py's own functions.
"""
import itertools
import os
import statistics

import cost_model_ratios as cmr
from study_page import NONE, num, opt

MODELS = ["extended", "coherent"]


def ratio_rows(reports, of_kind, model):
    """{(scene, class): (median |error|, worst |error|, pairs)} over the pairs of one kind."""
    out = {}
    for scene in sorted(reports):
        candidates = sorted(reports[scene], key=cmr.candidate_order)
        first = next(iter(reports[scene][candidates[0]].values()))
        for cls in first["cost"]["per_class"]:
            counts = [r["rays"][cls]["count"] for c in candidates for r in reports[scene][c].values()]
            if min(counts) < cmr.MIN_RAYS:
                continue
            errors = [abs(e) for a, b in itertools.combinations(candidates, 2) if of_kind(a, b)
                      for e in [cmr.pair_error(reports[scene][a], reports[scene][b], cls, model)] if e is not None]
            if errors:
                out[(scene, cls)] = (statistics.median(errors), max(errors), len(errors))
    return out


def meets(row):
    return row[0] <= cmr.TARGET_MEDIAN and row[1] <= cmr.TARGET_WORST


def ratios_section(page, data_dir, meta, record):
    """Returns {kind title: {model: (rows meeting, rows)}} for the page's findings, or {} when not measured."""
    page.add("## 6. The cost model judged on choosing")
    page.add()
    folder = os.path.join(data_dir, "ratios")
    reports = cmr.load(folder) if os.path.isdir(folder) else {}
    if not reports:
        page.para("Not measured in this run (%s): the full run measures it on the shared scenes with "
                  "`tools/cost_model_check.sh --ratios`." %
                  ("a quick run" if meta["mode"] == "quick" else "no shared scenes, or a restricted run"))
        return {}
    # Scenes the calibration measured are shown, marked, and left out of the counts: the target is for
    # scenes out of the calibration sample.
    any_report = next(iter(next(iter(next(iter(reports.values())).values())).values()))
    calibration = any_report["cost"].get("calibration")
    in_sample = cmr.calibrated_scenes(calibration) if calibration and os.path.isfile(calibration) else set()
    models = [m for m in MODELS if all(r["cost"].get(m) for by_c in reports.values() for by_r in by_c.values()
                                        for r in by_r.values())]
    kinds = cmr.PAIR_KINDS[:2]
    rows = {title: {m: ratio_rows(reports, of_kind, m) for m in models} for title, of_kind in kinds}
    summary = {title: {m: (sum(meets(r) for k, r in rows[title][m].items() if k[0] not in in_sample),
                           sum(1 for k in rows[title][m] if k[0] not in in_sample)) for m in models}
               for title, _ in kinds}
    runs = max(len(by_r) for by_c in reports.values() for by_r in by_c.values())
    res_title, g2_title = kinds[0][0], kinds[1][0]
    best = max(models, key=lambda m: summary[res_title][m][0])
    page.para("**A choice needs the ratio of two candidates' costs, not their seconds: the %s model predicts the "
              "ratio of two grid resolutions' costs within the target (median |error| ≤ %s, worst ≤ %s) on %d of "
              "%d scene-class rows, and grid's against grid2's on %d of %d.** A ratio measured with the "
              "candidates taking turns in one run is free of the machine's drift, which an absolute prediction "
              "is not." %
              (best, num(cmr.TARGET_MEDIAN), num(cmr.TARGET_WORST), summary[res_title][best][0],
               summary[res_title][best][1], summary[g2_title][best][0], summary[g2_title][best][1]))
    args_path = os.path.join(data_dir, "ratios.args")
    command = open(args_path).read().strip() if os.path.exists(args_path) else "tools/cost_model_check.sh --ratios"
    densities = sorted({float(c.split("-", 1)[1]) for by_c in reports.values() for c in by_c if c.startswith("grid-")})
    page.para("`%s` (%d runs): each shared scene rendered with statistics on through the grid at λ = %s and "
              "through grid2, every candidate in turn within each run. For each pair of candidates and ray class, the error is "
              "(predicted_A / predicted_B) / (measured_A / measured_B) − 1 in one run, its median over the runs "
              "the pair's; a row gives the median and the worst |error| over its pairs (classes of at least %s "
              "rays). The extended model is eq 10 with per-class constants, occupied cells, hits and cache misses "
              "(a step's by the bytes of the cells, a test's by those of the lists and triangles), and for grid2 a "
              "cost per sub-grid entered; the coherent model adds a cost per cold cell step (a "
              "cell the tile's recent walks did not enter: `stats/recent_cells.h`). The "
              "calibration: `%s`." %
              (command, runs, ", ".join(num(d) for d in densities), num(cmr.MIN_RAYS),
               os.path.basename(calibration) if calibration else NONE))
    for title, _ in kinds:
        page.add("### %s" % title)
        page.add()
        keys = sorted(set().union(*(rows[title][m].keys() for m in models)))
        table_rows = []
        for scene, cls in keys:
            cells = [scene + (" (in the calibration)" if scene in in_sample else ""), cls]
            for m in models:
                r = rows[title][m].get((scene, cls))
                cells += [opt(r[0] if r else None), opt(r[1] if r else None), ("yes" if meets(r) else "no") if r else NONE]
            table_rows.append(cells)
        header = ["scene", "class"]
        kinds_col = ["text", "text"]
        for m in models:
            header += ["%s median" % m, "%s worst" % m, "%s meets" % m]
            kinds_col += ["num?", "num?", "text"]
        page.table(header, kinds_col, table_rows)
        page.para("Rows meeting the target: " + "; ".join("%s model %d of %d" % (m, *summary[title][m])
                                                          for m in models) + ".")
    record["ratios"] = {title: {m: {"meeting": summary[title][m][0], "rows": summary[title][m][1]} for m in models}
                        for title, _ in kinds}
    return summary
