#!/usr/bin/python3
"""Writes run_file/seed_v3_chunked.h5 with casmap's own writer (format 3, HDF5 1.6 layout:
version 1 object headers, so the fuzzer reaches the dataset header decoders without checksums):
6 scans x 181 beams (chunked and deflated: 1 086 elements), 3 poses and 4 x 4 maps.
Regenerate (from the repository root, after building the Python module):
    PYTHONPATH=build/python /usr/bin/python3 tests/data/fuzz/make_casmap_seed.py"""
import numpy as np

import casmap._casmap as c

n, b = 6, 181
ranges = np.tile(np.linspace(0.5, 7.5, b, dtype=np.float32), (n, 1))
run = {
    "scans": {
        "stamp_s": np.arange(n) / 75.0,
        "ranges_m": ranges,
        "raw": (ranges * 1000).astype(np.uint16),
        "status": np.zeros((n, b), np.uint8),
        "labels": np.ones((n, b), np.uint8),
        "true_range_m": None,
        "start_angle_rad": -np.pi / 2,
        "angle_step_rad": np.pi / 180,
        "beam_period_s": 3.7e-05,
        "beam_time_offset_s": None,
    },
    "poses": {
        "stamp_s": np.array([0.0, 0.05, 0.1]),
        "xyz_m": np.array([[0.0, 0, 1], [0.05, 0, 1], [0.1, 0, 1]]),
        "quat_xyzw": np.array([[0.0, 0, 0, 1]] * 3),
    },
    "maps": {
        "grid": c.Grid(0.0, -0.05, 0.025, 4, 4),
        "elevation_m": np.linspace(0, 0.15, 16, dtype=np.float32).reshape(4, 4),
        "certainty": np.full((4, 4), 3, np.float32),
        "truth_m": None,
        "filtered": {},
    },
    "seed": 7,
    "config_yaml": "scene: course04.yaml\nmotion: T\n",
    "format": ("8m", "mm"),
}
c._write_run("tests/data/fuzz/run_file/seed_v3_chunked.h5", run)
