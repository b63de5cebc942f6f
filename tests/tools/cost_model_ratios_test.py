#!/usr/bin/python3
"""tools/cost_model_ratios.py on reports whose answer is known:

    tests/tools/cost_model_ratios_test.py REPO

Scene "s", three candidates, three runs. Every run measures grid-8 at 2 s, grid-32 at 1 s and grid2 at
1 s for the camera class; the model predicts 2, 1 and 1.5 s, so the pairs' errors are 0 (grid-8 / grid-32),
-1/3 (grid-8 / grid2: 2/1.5 over 2/1) and -1/3 (grid-32 / grid2), except that run 2 measures grid2 at
0.5 s (errors -2/3 there): the median over runs keeps -1/3. All pairs: median 1/3, worst 1/3; the grid
resolutions' one pair: 0; grid against grid2: 1/3 and 1/3. The shadow class has fewer than 1e5 rays in one
candidate, so it has no row. The same reports with the coherent model's predictions (each class's measured
seconds: every error 0) add its three tables, every row meeting the target. Exit 0 when the tables say so.
"""
import json
import os
import subprocess
import sys
import tempfile


def report(camera, shadow_rays=200000, coherent=False):
    predicted, measured = camera
    r = {"rays": {"camera": {"count": 262144}, "shadow": {"count": shadow_rays}},
         "cost": {"per_class": {"camera": {"extended_s": predicted, "measured_s": measured},
                                "shadow": {"extended_s": 1.0, "measured_s": 1.0}}}}
    if coherent:
        r["cost"]["coherent"] = {"predicted_s": 1.0}
        for entry in r["cost"]["per_class"].values():
            entry["coherent_s"] = entry["measured_s"]
    return r


def write_runs(folder, coherent=False):
    for run in (1, 2, 3):
        grid2_measured = 0.5 if run == 2 else 1.0
        cases = {"grid-8": report((2.0, 2.0), coherent=coherent),
                 "grid-32": report((1.0, 1.0), shadow_rays=5, coherent=coherent),
                 "grid2": report((1.5, grid2_measured), coherent=coherent)}
        for name, r in cases.items():
            with open(os.path.join(folder, f"s.{name}.{run}.json"), "w") as f:
                json.dump(r, f)


def main():
    repo = sys.argv[1]
    with tempfile.TemporaryDirectory() as folder:
        write_runs(folder)
        out = subprocess.run(["/usr/bin/python3", os.path.join(repo, "tools", "cost_model_ratios.py"), folder, "3"],
                             capture_output=True, text=True)
        failures = []
        if out.returncode != 0:
            failures.append(f"exit {out.returncode}: {out.stderr}")
        sections = out.stdout.split("\n### ")[1:]
        expected = [("grid resolutions", "| s | camera | 262144 | 1 | 0.000 | 0.000 |", "1 of 1"),
                    ("grid against grid2", "| s | camera | 262144 | 2 | 0.333 | 0.333 |", "0 of 1"),
                    ("all pairs", "| s | camera | 262144 | 3 | 0.333 | 0.333 |", "0 of 1")]
        if len(sections) != len(expected):
            failures.append(f"expected {len(expected)} tables: {out.stdout}")
        for section, (title, row, summary) in zip(sections, expected):
            rows = [l for l in section.splitlines() if l.startswith("| s |")]
            if not section.startswith(title) or len(rows) != 1 or not rows[0].startswith(row):
                failures.append(f"{title}: expected the one row {row}: {section}")
            if f"{summary} scene-class rows out of the calibration meet the target" not in section:
                failures.append(f"{title}: the summary is not '{summary}': {section}")
        # A calibration that measured "s": its rows are marked and counted in no summary.
        calibration = os.path.join(folder, "calibration.json.txt")
        with open(calibration, "w") as f:
            json.dump({"measurements": [{"label": "s 4x4x4 camera"}]}, f)
        marked = subprocess.run(["/usr/bin/python3", os.path.join(repo, "tools", "cost_model_ratios.py"), folder, "3",
                                 calibration], capture_output=True, text=True).stdout
        if marked.count("| s (in the calibration) | camera |") != 3 or marked.count("0 of 0 scene-class rows") != 3:
            failures.append(f"a scene of the calibration is not marked and left out of the summaries: {marked}")
        # The coherent model's tables, from its own predictions.
        with tempfile.TemporaryDirectory() as both:
            write_runs(both, coherent=True)
            out = subprocess.run(["/usr/bin/python3", os.path.join(repo, "tools", "cost_model_ratios.py"), both, "3"],
                                 capture_output=True, text=True).stdout
            coherent = out.split("## The coherent model")[1:]
            if len(coherent) != 1 or coherent[0].count("coherent: 1 of 1 scene-class rows") != 3 \
                    or coherent[0].count("| s | camera | 262144 |") != 3 or "extended: 0 of 1" not in out:
                failures.append(f"the coherent model's tables are not its own: {out}")
            # One report without the coherent model (an older calibration's): no coherent tables, and a word why.
            with open(os.path.join(both, "s.grid2.2.json"), "w") as f:
                json.dump(report((1.5, 0.5)), f)
            partial = subprocess.run(["/usr/bin/python3", os.path.join(repo, "tools", "cost_model_ratios.py"), both, "3"],
                                     capture_output=True, text=True)
            if "## The coherent model" in partial.stdout or "no coherent tables" not in partial.stderr:
                failures.append(f"a report without the coherent model: {partial.stdout} {partial.stderr}")
        with tempfile.TemporaryDirectory() as empty:
            code = subprocess.run(["/usr/bin/python3", os.path.join(repo, "tools", "cost_model_ratios.py"), empty, "1"],
                                  capture_output=True).returncode
            if code != 2:
                failures.append(f"a folder without reports: exit {code}, not 2")
    for f in failures:
        print("cost_model_ratios_test:", f, file=sys.stderr)
    if failures:
        sys.exit(1)
    print("cost_model_ratios_test: ok")


if __name__ == "__main__":
    main()
