#!/usr/bin/python3
"""Rewrites the built-in constants in stats/builtin_calibration.cpp from a
calibration file (kappa_calibration.json, written by `kappa calibrate`):

    tools/builtin_calibration.py CAL.json --date YYYY-MM-DD --load L [--repeat N]

The file's constants only (its measurements left out), as compact JSON in
raw-string pieces of 100 characters, so that the built-in constants are
always a real calibrate run's.
"""
import argparse
import json
import os
import re

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "stats", "builtin_calibration.cpp")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("calibration")
    p.add_argument("--date", required=True, help="the day calibrate ran")
    p.add_argument("--load", required=True, help="the load average uptime showed")
    p.add_argument("--repeat", type=int, default=3, help="calibrate's --repeat (its default: 3)")
    a = p.parse_args()
    with open(a.calibration) as f:
        cal = json.load(f)
    # Every model's constants, the coherent one's too (--grid-res model predicts with it, stats/README.md);
    # not the machine probe's time: the built-in constants serve any machine, and a report compares a
    # probe only with its own calibration's.
    kept = {k: v for k, v in cal.items() if not k.endswith(("measurements", "builds")) and k != "machine_probe_s"}
    text = json.dumps(kept, separators=(",", ":"))
    pieces = "\n".join(f'    R"({text[i:i + 100]})"' for i in range(0, len(text), 100))
    with open(SOURCE) as f:
        src = f.read()
    src, n = re.subn(r'(// Fitted by .*?\n)(// .*?\n)*?constexpr const char\* kBuiltinConstants =\n(    R"\(.*?\)"\n?)+;',
                     lambda m: (f"// Fitted by `build/kappa calibrate --repeat {a.repeat}` (its default scenes: the\n"
                                f"// Cornell box, the low-res bunny and the generated soups and meshes) on a project machine on\n"
                                f"// {a.date} (load average {a.load}), written in by tools/builtin_calibration.py:\n"
                                f"// the calibration file's own constants, its measurements left out.\n"
                                f"constexpr const char* kBuiltinConstants =\n{pieces};"),
                     src, flags=re.S)
    if n != 1:
        raise SystemExit("builtin_calibration.py: the constants were not found in " + SOURCE)
    tmp = SOURCE + ".part"
    with open(tmp, "w") as f:
        f.write(src)
    os.replace(tmp, SOURCE)


if __name__ == "__main__":
    main()
