"""The CAS filter on an elevation/certainty TIFF pair (what `casmap map` writes), then the
paper's Table II classes: the share of removed, filled and untouched cells.

    python3 filter_tiff.py H.tiff C.tiff [NAME=VALUE ...]

NAME=VALUE pairs are CAS parameters as `casmap filter --set` names them (k=3, A=12, ...).
"""
import sys

import numpy as np

import casmap

if len(sys.argv) < 3:
    sys.exit(f"usage: {sys.argv[0]} H.tiff C.tiff [NAME=VALUE ...]")

# 32-bit float TIFFs -> float32 arrays, rows along-track.
elevation = casmap.read_map_tiff(sys.argv[1])
certainty = casmap.read_map_tiff(sys.argv[2])
params = dict(arg.split("=", 1) for arg in sys.argv[3:])  # values as text, like --set

try:
    filtered, classes = casmap.filter("cas", elevation, certainty, **params)
except ValueError as err:  # the message names the parameter and the rule
    sys.exit(f"filter_tiff.py: {err}")

shares = casmap.cas_classes_percent(classes, certainty)
print(f"{elevation.shape[0]}x{elevation.shape[1]} cells, {shares['cells']} processed")
for name in ("all", "observed"):
    s = shares if name == "all" else shares["observed"]
    print(f"{name + ':':9s} removed {s['removed']:.2f} %  filled {s['filled']:.2f} %  "
          f"untouched {s['untouched']:.2f} %")
print(f"largest change: {np.max(np.abs(filtered - elevation)):.3f} m")
