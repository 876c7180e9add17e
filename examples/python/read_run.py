"""Open a run file (`casmap simulate` or `casmap record` output), walk its scans and poses,
and count the beams per status and, for simulated runs, per truth label.

    python3 read_run.py RUN.h5
"""
import sys

import numpy as np

import casmap

if len(sys.argv) != 2:
    sys.exit(f"usage: {sys.argv[0]} RUN.h5")
try:
    run = casmap.read_run(sys.argv[1])
except ValueError as err:  # the message names the file, the dataset and the rule
    sys.exit(f"read_run.py: {err}")
scans, poses = run.scans, run.poses
print(f"{len(scans.stamp_s)} scans of {scans.ranges_m.shape[1]} beams, "
      f"{len(poses.stamp_s)} poses, seed {run.seed}")

# Walk the scans: the sensor's world position at each scan's first beam (interpolated
# linearly between pose samples), and how far the sensor travelled.
if len(poses.stamp_s):
    x = np.interp(scans.stamp_s, poses.stamp_s, poses.xyz_m[:, 0])
    print(f"sensor x from {x.min():.3f} m to {x.max():.3f} m")

# Beams per status (every run) and per truth label (simulated runs).
for code, name in enumerate(casmap.BEAM_STATUS):
    print(f"status {name:12s} {np.count_nonzero(scans.status == code)}")
if scans.labels is not None:
    for code, name in enumerate(casmap.BEAM_LABELS):
        print(f"label  {name:12s} {np.count_nonzero(scans.labels == code)}")
