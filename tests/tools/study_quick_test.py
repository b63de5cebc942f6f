#!/usr/bin/python3
"""The results page's quick run, checked (issue #16):

    tests/tools/study_quick_test.py STUDY_SH|REPO BUILD_DIR     run tools/study.sh --quick into a fresh
                                                                temporary folder and check what it wrote
    tests/tools/study_quick_test.py --check OUT_DIR             check a page already written (no run; the
                                                                quick run's plots only if it is a quick page)

Runs `tools/study.sh --quick --out TMP` with KAPPA_BIN=BUILD_DIR/kappa and checks: exit status 0;
results.md and results/manifest.json exist; the page's tables are the manifest's (same count, headers
and rows) and every cell holds what its column's kind says (num: a finite number; num?: a finite number
or the report's "—" for a null; res: NxNxN; text: not empty), and no cell anywhere reads nan, inf, None
or null; every PNG the page shows exists, is a PNG whose IHDR gives the manifest's size, and decodes
(matplotlib) to that size; the manifest names no PNG the page does not show; the quick run's own plots
are there; no temporary file is left; and the repo's committed docs/ is exactly as before (every file's
bytes and mtime). Exit 0 when all hold, 1 naming each failure.
Run with /usr/bin/python3 (numpy and matplotlib: tools/setup.sh).
"""
import hashlib
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?")
RES = re.compile(r"(\d+)x(\d+)x(\d+)")
NONE = "—"
BAD_WORDS = re.compile(r"\b(nan|inf|infinity|none|null)\b", re.IGNORECASE)
# What the quick run must plot: one sweep per assets/ scene, the kappa bars, the scaling study.
QUICK_PNGS = ["results/sweep-cornell-box.png", "results/sweep-bunny-lowres.png", "results/kappa.png", "results/accels.png",
              "results/scaling.png"]
HANG_GUARD_S = 900  # the quick run should take under 3 minutes; this only stops a hang


def tables(markdown):
    """Every table of the page: (header cells, [row cells]), blocks of lines starting with '|'."""
    out, block = [], []
    for line in markdown.splitlines() + [""]:
        if line.startswith("|"):
            block.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif block:
            out.append((block[0], block[2:], block[1]))
            block = []
    return out


def png_size(path):
    """(width, height) from the PNG's IHDR, or None when it is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_cell(kind, cell):
    if BAD_WORDS.search(cell):
        return "reads like a non-number"
    if kind in ("num", "num?"):
        if kind == "num?" and cell == NONE:
            return None
        if not NUMBER.fullmatch(cell):
            return "is not a number"
        if not math.isfinite(float(cell)):
            return "is not finite"
        return None
    if kind == "res":
        m = RES.fullmatch(cell)
        return None if m and all(int(g) > 0 for g in m.groups()) else "is not a resolution NxNxN"
    if kind == "text":
        return None if cell else "is empty"
    return "has an unknown kind %r" % kind


def check_output(out_dir, quick=True):
    """The list of failures of the page in out_dir (empty when it passes)."""
    import json

    fails = []
    page_path = os.path.join(out_dir, "results.md")
    manifest_path = os.path.join(out_dir, "results", "manifest.json")
    for p in (page_path, manifest_path):
        if not os.path.isfile(p):
            fails.append("missing: %s" % p)
    if fails:
        return fails
    with open(page_path) as f:
        page = f.read()
    with open(manifest_path) as f:
        manifest = json.load(f)
    found = tables(page)
    expected = manifest["tables"]
    if len(found) != len(expected):
        fails.append("the page has %d tables, the manifest %d" % (len(found), len(expected)))
    if not found:
        fails.append("the page has no table")
    for i, ((head, rows, sep), want) in enumerate(zip(found, expected)):
        where = "table %d (%s)" % (i + 1, " | ".join(head[:3]))
        if head != want["header"]:
            fails.append("%s: header differs from the manifest's %s" % (where, want["header"]))
            continue
        if len(sep) != len(head) or not all(re.fullmatch(r":?-{3,}:?", c) for c in sep):
            fails.append("%s: bad separator row %s" % (where, sep))
        if len(rows) != want["rows"] or not rows:
            fails.append("%s: %d rows, the manifest says %d" % (where, len(rows), want["rows"]))
        kinds = want["kinds"]
        for r, row in enumerate(rows):
            if len(row) != len(kinds):
                fails.append("%s, row %d: %d cells for %d columns" % (where, r + 1, len(row), len(kinds)))
                continue
            for kind, name, cell in zip(kinds, head, row):
                why = check_cell(kind, cell)
                if why:
                    fails.append("%s, row %d, column '%s': %r %s" % (where, r + 1, name, cell, why))
    shown = re.findall(r"!\[[^\]]*\]\(([^)\s]+)\)", page)
    if not shown:
        fails.append("the page shows no image")
    pngs = manifest.get("pngs", {})
    for rel in shown:
        path = os.path.join(out_dir, rel)
        if rel not in pngs:
            fails.append("%s: shown but not in the manifest" % rel)
            continue
        want = (pngs[rel]["width"], pngs[rel]["height"])
        if not os.path.isfile(path):
            fails.append("%s: shown but missing" % rel)
            continue
        size = png_size(path)
        if size is None:
            fails.append("%s: not a PNG" % rel)
            continue
        if size != want:
            fails.append("%s: IHDR says %dx%d, expected %dx%d" % (rel, *size, *want))
        try:
            import matplotlib.image

            pixels = matplotlib.image.imread(path)
            if (pixels.shape[1], pixels.shape[0]) != want:
                fails.append("%s: decodes to %dx%d, expected %dx%d" % (rel, pixels.shape[1], pixels.shape[0], *want))
        except Exception as e:  # a truncated or corrupt file
            fails.append("%s: does not decode: %s" % (rel, e))
    for rel in pngs:
        if rel not in shown:
            fails.append("%s: in the manifest but not shown by the page" % rel)
    if quick:
        for rel in QUICK_PNGS:
            if rel not in shown:
                fails.append("%s: the quick run's plot is not on the page" % rel)
    for root, _, files in os.walk(out_dir):
        for name in files:
            if ".tmp" in name or name.endswith(".part"):
                fails.append("temporary file left: %s" % os.path.join(root, name))
    for section in ("## The findings", "## 1.", "## 2.", "## 3.", "## 4.", "## 5.", "## 6."):
        if section not in page:
            fails.append("the page lacks its section '%s'" % section)
    # The opening states the study's findings, numbered, before the first section.
    opening = page.split("## 1.", 1)[0]
    if not re.search(r"^1\. \*\*", opening, re.M) or not re.search(r"^3\. \*\*", opening, re.M):
        fails.append("the page's opening does not state three numbered findings")
    return fails


def snapshot(folder):
    """Every file under folder: its bytes' SHA-256, size and mtime."""
    snap = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            st = os.stat(path)
            with open(path, "rb") as f:
                snap[os.path.relpath(path, folder)] = (hashlib.sha256(f.read()).hexdigest(), st.st_size, st.st_mtime_ns)
    return snap


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--check":
        # The quick run's own plots are expected only of a quick page (its data.json says which).
        quick = True
        try:
            import json

            with open(os.path.join(sys.argv[2], "results", "data.json")) as f:
                quick = json.load(f)["meta"]["mode"] == "quick"
        except (OSError, ValueError, KeyError):
            pass
        fails = check_output(sys.argv[2], quick)
        for f in fails:
            print("FAIL: " + f)
        print("study_quick_test: %s" % ("FAILED (%d)" % len(fails) if fails else "passed"))
        return 1 if fails else 0
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    target, build = sys.argv[1], sys.argv[2]
    study = os.path.join(target, "tools", "study.sh") if os.path.isdir(target) else target
    study = os.path.abspath(study)
    repo = os.path.dirname(os.path.dirname(study))
    kappa = os.path.abspath(os.path.join(build, "kappa"))
    for p in (study, kappa):
        if not os.path.isfile(p):
            sys.exit("study_quick_test: %s not found" % p)
    docs = os.path.join(repo, "docs")
    before = snapshot(docs)
    tmp = tempfile.mkdtemp(prefix="study-quick-test.")
    out = os.path.join(tmp, "out")  # fresh: study.sh creates it
    try:
        env = dict(os.environ, KAPPA_BIN=kappa)
        t0 = time.monotonic()
        try:
            run = subprocess.run(["bash", study, "--quick", "--out", out], env=env, timeout=HANG_GUARD_S,
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        except subprocess.TimeoutExpired:
            print("FAIL: tools/study.sh --quick ran over %d s" % HANG_GUARD_S)
            return 1
        seconds = time.monotonic() - t0
        fails = []
        if run.returncode != 0:
            print(run.stdout[-6000:])
            fails.append("tools/study.sh --quick exited %d" % run.returncode)
        else:
            fails += check_output(out)
        if snapshot(docs) != before:
            fails.append("the committed docs/ changed during the run")
        for f in fails:
            print("FAIL: " + f)
        print("study_quick_test: tools/study.sh --quick took %.0f s; %s" %
              (seconds, "FAILED (%d)" % len(fails) if fails else "passed"))
        return 1 if fails else 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
