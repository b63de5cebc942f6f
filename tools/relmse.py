#!/usr/bin/python3
"""relMSE of an image against a reference, as Kappa's budgets estimate it:
the mean over pixels and the R, G, B channels of (x - ref)^2 / (ref^2 + 0.01).

    tools/relmse.py IMAGE.exr REFERENCE.exr

Prints the relMSE, the RMSE, and the mean-image bias (mean(x) / mean(ref) - 1).
When the reference has variance channels (kappa render --aov variance), it also
prints the reference's own share of that relMSE, mean(var_ref / (ref^2 + 0.01)),
and the relMSE less it ("corrected"): the image's error against the true mean,
for a reference of fewer samples than would make its own noise negligible.
Needs python3-openimageio and python3-numpy (tools/setup.sh installs them);
run with /usr/bin/python3.
"""
import sys

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError as e:
    sys.exit(f"relmse.py: {e.name} is missing: run tools/setup.sh (python3-numpy, python3-openimageio)")


def channels(path, which):
    image = oiio.ImageBuf(path)
    if image.has_error:
        sys.exit(f"relmse.py: {path}: {image.geterror()}")
    names = list(image.spec().channelnames)
    if not all(c in names for c in which):
        return None
    pixels = image.get_pixels(oiio.FLOAT)
    return np.stack([pixels[:, :, names.index(c)] for c in which], axis=-1).astype(np.float64)


def rgb(path):
    return channels(path, ["R", "G", "B"])


if len(sys.argv) != 3:
    sys.exit(__doc__)
x, ref = rgb(sys.argv[1]), rgb(sys.argv[2])
if x.shape != ref.shape:
    sys.exit(f"relmse.py: sizes differ: {x.shape[1]}x{x.shape[0]} against {ref.shape[1]}x{ref.shape[0]}")
relmse = np.mean((x - ref) ** 2 / (ref ** 2 + 0.01))
rmse = np.sqrt(np.mean((x - ref) ** 2))
bias = x.mean() / ref.mean() - 1 if ref.mean() > 0 else float("nan")
line = f"relmse {relmse:.6g} rmse {rmse:.6g} bias {bias:+.4g}"
var_ref = channels(sys.argv[2], ["variance.R", "variance.G", "variance.B"])
if var_ref is not None:
    own = np.mean(var_ref / (ref ** 2 + 0.01))
    line += f" ref_relmse {own:.6g} corrected {relmse - own:.6g}"
print(line)
