#!/usr/bin/python3
"""Writes the binary fuzz seeds: a 4 x 3 float TIFF map and a tiny run file (2 scans x 5 beams).
Regenerate: /usr/bin/python3 tests/data/fuzz/make_seeds.py (from the repository root)."""
import struct

import h5py
import numpy as np


def tiff(path, rows, cols):
    pixels = np.arange(rows * cols, dtype="<f4").reshape(rows, cols) * 0.01
    data = pixels.tobytes()
    entries = [  # tag, type (3 SHORT, 4 LONG), value
        (256, 3, cols), (257, 3, rows), (258, 3, 32), (259, 3, 1), (262, 3, 1),
        (273, 4, 8), (277, 3, 1), (278, 3, rows), (279, 4, len(data)), (339, 3, 3)]
    ifd = struct.pack("<H", len(entries))
    for tag, typ, value in entries:
        packed = struct.pack("<HHI", tag, typ, 1)
        packed += struct.pack("<HH", value, 0) if typ == 3 else struct.pack("<I", value)
        ifd += packed
    ifd += struct.pack("<I", 0)
    with open(path, "wb") as f:
        f.write(b"II*\0" + struct.pack("<I", 8 + len(data)) + data + ifd)


def run_file(path):
    n, b = 2, 5
    with h5py.File(path, "w", libver="latest") as f:
        f.attrs["casmap_run_format_version"] = np.int32(1)
        f.attrs["config_yaml"] = "seed: 1\n"
        s = f.create_group("scans")
        s["stamp_s"] = np.array([0.0, 1.0 / 75], dtype="<f8")
        s["ranges_m"] = np.full((n, b), 1.5, dtype="<f4")
        s["raw"] = np.full((n, b), 1500, dtype="<u2")
        s["status"] = np.zeros((n, b), dtype="u1")
        s["labels"] = np.zeros((n, b), dtype="u1")
        s.attrs["start_angle_rad"] = 0.0
        s.attrs["angle_step_rad"] = 0.0174533
        s.attrs["beam_period_s"] = 3.7e-5
        s.attrs["range_mode"] = "8m"
        s.attrs["range_units"] = "mm"
        p = f.create_group("poses")
        p["stamp_s"] = np.array([0.0, 1.0], dtype="<f8")
        p["xyz_m"] = np.array([[0, 0, 1], [0.2, 0, 1]], dtype="<f8")
        p["quat_xyzw"] = np.array([[0, 0, 0, 1], [0, 0, 0, 1]], dtype="<f8")
        m = f.create_group("maps")
        m.attrs["origin_x_m"] = 0.0
        m.attrs["origin_y_m"] = 0.0
        m.attrs["cell_m"] = 0.025
        m.attrs["rows"] = np.int32(2)
        m.attrs["cols"] = np.int32(2)
        m["elevation_m"] = np.zeros((2, 2), dtype="<f4")


tiff("tests/data/fuzz/tiff_map/seed_4x3.tiff", 4, 3)
run_file("tests/data/fuzz/run_file/seed_2x5.h5")
