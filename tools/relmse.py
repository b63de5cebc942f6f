#!/usr/bin/python3
"""relMSE of an image against a reference, as Kappa's budgets estimate it:
the mean over pixels and the R, G, B channels of (x - ref)^2 / (ref^2 + 0.01).

    tools/relmse.py IMAGE.exr REFERENCE.exr

Prints the relMSE, the RMSE, and the mean-image bias (mean(x) / mean(ref) - 1).
Needs python3-openimageio and python3-numpy (tools/setup.sh installs them);
run with /usr/bin/python3.
"""
import sys

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError as e:
    sys.exit(f"relmse.py: {e.name} is missing: run tools/setup.sh (python3-numpy, python3-openimageio)")


def rgb(path):
    image = oiio.ImageBuf(path)
    if image.has_error:
        sys.exit(f"relmse.py: {path}: {image.geterror()}")
    spec = image.spec()
    names = list(spec.channelnames)
    pixels = image.get_pixels(oiio.FLOAT)
    return np.stack([pixels[:, :, names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)


if len(sys.argv) != 3:
    sys.exit(__doc__)
x, ref = rgb(sys.argv[1]), rgb(sys.argv[2])
if x.shape != ref.shape:
    sys.exit(f"relmse.py: sizes differ: {x.shape[1]}x{x.shape[0]} against {ref.shape[1]}x{ref.shape[0]}")
relmse = np.mean((x - ref) ** 2 / (ref ** 2 + 0.01))
rmse = np.sqrt(np.mean((x - ref) ** 2))
bias = x.mean() / ref.mean() - 1 if ref.mean() > 0 else float("nan")
print(f"relmse {relmse:.6g} rmse {rmse:.6g} bias {bias:+.4g}")
