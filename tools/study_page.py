"""The results page's building blocks (tools/study_report.py and its sections): number formatting that
never prints nan or None, the page with what its manifest records of each table and figure, the plots'
sizes and the one colour of each ray class on every figure, and the readers of the raw outputs.
"""
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Every figure is saved at FIGSIZE * DPI pixels exactly (no tight bounding box), so a test can check it.
DPI = 80
FIGSIZE = {"sweep": (13.0, 3.5), "kappa": (11.0, 4.5), "scaling": (14.0, 6.5), "accels": (11.0, 4.5)}
RENDER_CLASSES = ["camera", "shadow", "bounce1", "bounce2", "bounce3+"]
# One colour per ray class on every figure (and for the sweep's own classes: bounce as bounce1, lines grey).
CLASS_COLOURS = {"camera": "tab:blue", "shadow": "tab:orange", "bounce1": "tab:green", "bounce2": "tab:red",
                 "bounce3+": "tab:purple", "bounce": "tab:green", "lines": "tab:gray", "all": "black"}
NONE = "—"  # a value the report has as null (no rays of a class, no prediction); only in "num?" columns


def finite(x):
    return x is not None and isinstance(x, (int, float)) and math.isfinite(x)


def num(x, sig=3):
    """A finite number with sig significant digits, without exponent between 1e-3 and 1e7."""
    if not finite(x):
        raise ValueError("not a finite number: %r" % (x,))
    if x == 0:
        return "0"
    if float(x).is_integer() and abs(x) < 1e7:
        return "%d" % x  # counts (N, N_c, rays) as they are
    mag = math.floor(math.log10(abs(x)))
    if -3 <= mag < 7:
        decimals = max(0, sig - 1 - mag)
        return "%.*f" % (decimals, round(x, decimals))
    return "%.*e" % (sig - 1, x)


def opt(x, sig=3):
    """num(x), or NONE when the report holds no value."""
    return num(x, sig) if finite(x) else NONE


def ratio(x):
    """A ratio of costs, always two decimals so that a column reads evenly."""
    if not finite(x):
        raise ValueError("not a finite ratio: %r" % (x,))
    return "%.2f" % x


def opt_ratio(x):
    return ratio(x) if finite(x) else NONE


def pct(x):
    return num(100.0 * x, 2)



class Page:
    """Markdown lines, plus what the manifest records of each table and figure."""

    def __init__(self, out_dir):
        self.lines = []
        self.tables = []
        self.pngs = {}
        self.out_dir = out_dir
        self.staged = []  # (temporary path, final path)

    def add(self, text=""):
        self.lines.append(text)

    def para(self, text):
        self.lines += [text, ""]

    def table(self, header, kinds, rows):
        """kinds per column: text, res (NxNxN), num (finite number), num? (finite number or NONE)."""
        assert len(header) == len(kinds)
        for row in rows:
            assert len(row) == len(kinds), (header, row)
        self.lines.append("| " + " | ".join(header) + " |")
        self.lines.append("|" + "|".join("---" if k in ("text", "res") else "---:" for k in kinds) + "|")
        for row in rows:
            self.lines.append("| " + " | ".join(row) + " |")
        self.lines.append("")
        self.tables.append({"header": header, "kinds": kinds, "rows": len(rows)})

    def figure(self, fig, name, kind, alt):
        rel = "results/%s.png" % name
        final = os.path.join(self.out_dir, rel)
        tmp = final + ".tmp%d" % os.getpid()
        fig.savefig(tmp, dpi=DPI, format="png")
        plt.close(fig)
        w, h = FIGSIZE[kind]
        self.pngs[rel] = {"width": int(round(w * DPI)), "height": int(round(h * DPI))}
        self.staged.append((tmp, final))
        self.lines += ["![%s](%s)" % (alt, rel), ""]


def new_figure(kind, rows=1, cols=1):
    return plt.subplots(rows, cols, figsize=FIGSIZE[kind], squeeze=False)


def read_json(path):
    with open(path) as f:
        return json.load(f)


def read_tsv(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [line.rstrip("\n").split("\t") for line in f if line.strip()]
