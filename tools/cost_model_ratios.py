#!/usr/bin/python3
"""The cost model judged on choosing (tools/cost_model_check.sh --ratios):

    tools/cost_model_ratios.py DIR RUNS [CALIBRATION.json]

DIR holds reports named SCENE.CANDIDATE.RUN.json (CANDIDATE: grid-8, grid-32, grid2, ...), every candidate
of a scene rendered in turn within each run. For each pair of candidates (A, B) and ray class, the error of
one run is (predicted_A / predicted_B) / (measured_A / measured_B) - 1, with a model's predicted
seconds and the class's measured seconds (the report's cost.per_class); a pair's error is its median over
the runs. The tables are given for the extended model, then for the coherent one (its cold-step terms,
stats/recent_cells.h) when every report has its predictions. Per scene and class of at least 1e5 rays (in every candidate), a table gives the median and the
worst |error| over the pairs, against the targets 0.10 and 0.25: one table for the pairs of grid resolutions
(the choice of --grid-res model), one for grid against grid2 (a choice of --accel auto), one for all pairs.
A scene the calibration measured (its measurements' labels begin with the scene's name) is marked so and
left out of the summaries: the target is for scenes out of the calibration sample. Exit 0 (a table is a measurement, not a
verdict); exit 2 when DIR holds no report.
"""
import glob
import itertools
import json
import os
import statistics
import sys

MIN_RAYS = 100000
TARGET_MEDIAN, TARGET_WORST = 0.10, 0.25


def load(folder):
    """{scene: {candidate: {run: report}}}"""
    reports = {}
    for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
        scene, candidate, run = os.path.basename(path)[:-5].rsplit(".", 2)
        with open(path) as f:
            reports.setdefault(scene, {}).setdefault(candidate, {})[int(run)] = json.load(f)
    return reports


def class_seconds(report, cls, model):
    """(predicted, measured) seconds of one class by `model`, or None when either is missing or not positive."""
    entry = report["cost"]["per_class"].get(cls)
    if not entry:
        return None
    predicted, measured = entry.get(model + "_s"), entry.get("measured_s")
    if not predicted or not measured or predicted <= 0 or measured <= 0:
        return None
    return predicted, measured


def pair_error(runs_a, runs_b, cls, model):
    """The median over the runs both candidates have of the run's ratio error, or None."""
    errors = []
    for run in sorted(set(runs_a) & set(runs_b)):
        a, b = class_seconds(runs_a[run], cls, model), class_seconds(runs_b[run], cls, model)
        if a and b:
            errors.append((a[0] / b[0]) / (a[1] / b[1]) - 1.0)
    return statistics.median(errors) if errors else None


def candidate_order(name):
    """grid at ascending density, then grid2."""
    accel, _, density = name.partition("-")
    return (accel, float(density) if density else 0.0)


# The kinds of pair, each a choice Kappa makes: (title, whether a pair (a, b) is of the kind).
PAIR_KINDS = [
    ("grid resolutions (--grid-res model)", lambda a, b: a.startswith("grid-") and b.startswith("grid-")),
    ("grid against grid2 (--accel auto)", lambda a, b: (a == "grid2") != (b == "grid2")),
    ("all pairs", lambda a, b: True),
]


def calibrated_scenes(path):
    """The scene names a calibration file measured (the first word of each measurement's label)."""
    if not path:
        return set()
    with open(path) as f:
        calibration = json.load(f)
    return {m["label"].split(" ")[0] for m in calibration.get("measurements", [])}


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: cost_model_ratios.py DIR RUNS [CALIBRATION.json]")
    folder, runs = sys.argv[1], int(sys.argv[2])
    in_sample = calibrated_scenes(sys.argv[3] if len(sys.argv) == 4 else None)
    reports = load(folder)
    if not reports:
        print(f"cost_model_ratios: no report in {folder}", file=sys.stderr)
        sys.exit(2)
    models = ["extended"]
    if all(r["cost"].get("coherent") for by_candidate in reports.values() for by_run in by_candidate.values()
           for r in by_run.values()):
        models.append("coherent")
    else:
        print("cost_model_ratios: no coherent tables: a report has no cost.coherent (its calibration file has no "
              "coherent model: run kappa calibrate again)", file=sys.stderr)
    for model in models:
        print(f"\n## The {model} model\n\nThe ratio of two candidates' predicted seconds over the ratio measured in "
              f"the same run, median of {runs} runs per pair; classes of at least {MIN_RAYS:g} rays.")
        for title, of_kind in PAIR_KINDS:
            table(reports, title, of_kind, in_sample, model)


def table(reports, title, of_kind, in_sample, model):
    """One Markdown table of the pairs of one kind, and its summary line."""
    print(f"\n### {title}, {model} model\n")
    print("| scene | class | rays (first candidate) | pairs | median \\|error\\| | worst \\|error\\| | worst pair (error) |")
    print("|---|---|---:|---:|---:|---:|---|")
    met = total = 0
    worst_overall = 0.0
    for scene in sorted(reports):
        candidates = sorted(reports[scene], key=candidate_order)
        first = next(iter(reports[scene][candidates[0]].values()))
        for cls in first["cost"]["per_class"]:
            counts = [r["rays"][cls]["count"] for c in candidates for r in reports[scene][c].values()]
            if min(counts) < MIN_RAYS:
                continue
            errors = {}
            for a, b in itertools.combinations(candidates, 2):
                if not of_kind(a, b):
                    continue
                e = pair_error(reports[scene][a], reports[scene][b], cls, model)
                if e is not None:
                    errors[(a, b)] = e
            if not errors:
                continue
            magnitudes = [abs(e) for e in errors.values()]
            median, worst = statistics.median(magnitudes), max(magnitudes)
            worst_pair = max(errors, key=lambda p: abs(errors[p]))
            shown = scene
            if scene in in_sample:
                shown += " (in the calibration)"
            else:
                total += 1
                met += median <= TARGET_MEDIAN and worst <= TARGET_WORST
                worst_overall = max(worst_overall, worst)
            print(f"| {shown} | {cls} | {first['rays'][cls]['count']} | {len(errors)} | {median:.3f} | {worst:.3f} | "
                  f"{worst_pair[0]} / {worst_pair[1]} ({errors[worst_pair]:+.3f}) |")
    print(f"\n{model}: {met} of {total} scene-class rows out of the calibration meet the target (median |error| <= {TARGET_MEDIAN}, worst <= "
          f"{TARGET_WORST}); the worst |error| of any such pair: {worst_overall:.3f}")


if __name__ == "__main__":
    main()
