#!/usr/bin/python3
"""Writes the binary files of the bad-input corpus (run files, TIFFs, meshes); the text files
beside them are written by hand. Regenerate: cd tests/data/bad_inputs && /usr/bin/python3
make_bad_inputs.py. cases.tsv lists the commands that use them."""
import math
import struct

import h5py
import numpy as np


def run(path, n=3, b=5, **change):
    stamps = change.get("stamps", np.arange(n) / 75.0)
    ranges = np.full((n, b), 1.5, dtype="<f4")
    if "range" in change:
        ranges[1, 2] = change["range"]
    with h5py.File(path, "w", libver="latest") as f:
        f.attrs["casmap_run_format_version"] = np.int32(1)
        f.attrs["config_yaml"] = "seed: 1\n"
        s = f.create_group("scans")
        s["stamp_s"] = np.asarray(stamps, dtype="<f8")
        s["ranges_m"] = ranges
        s["raw"] = np.full((n, b), 1500, dtype="<u2")
        s["status"] = np.zeros((n, b), dtype="u1")
        s.attrs["start_angle_rad"] = 0.0
        s.attrs["angle_step_rad"] = change.get("step", 0.0174533)
        s.attrs["beam_period_s"] = change.get("period", 3.7e-5)
        p = f.create_group("poses")
        poses = change.get("poses", 2)
        p["stamp_s"] = np.arange(poses, dtype="<f8")
        p["xyz_m"] = np.tile(np.array([0.0, 0.0, 1.0]), (poses, 1))
        p["quat_xyzw"] = np.tile(np.array([0.0, 0.0, 0.0, 1.0]), (poses, 1))


run("run_negative_range.h5", range=-1.0)
run("run_zero_angle_step.h5", step=0.0)
run("run_negative_beam_period.h5", period=-1.0)
run("run_reversed_stamps.h5", stamps=[0.0, 0.02, 0.01])
run("run_equal_stamps.h5", stamps=[0.0, 0.01, 0.01])
run("run_no_scans.h5", n=0)
run("run_no_poses.h5", poses=0)

# 1e9 x 181 scans declared, nothing stored: a few kilobytes.
with h5py.File("run_huge_declared.h5", "w") as f:
    s = f.create_group("scans")
    s.create_dataset("stamp_s", shape=(10**9,), dtype="<f8", chunks=(1024,), fillvalue=0.0)
    s.create_dataset("ranges_m", shape=(10**9, 181), dtype="<f4", chunks=(64, 181))

# run_corrupt_global_heap.h5 is not written here: it is libFuzzer's input that made HDF5 1.10.8
# loop forever in H5HG_read (docs/fuzzing.md), kept byte for byte.

with open("not_hdf5.h5", "wb") as f:
    f.write(b"this is not an HDF5 file\n")


def tiff_header(w, h):
    tags = [(256, 4, w), (257, 4, h), (258, 3, 32), (259, 3, 1), (262, 3, 1), (273, 4, 200),
            (277, 3, 1), (278, 4, 1), (279, 4, 4), (339, 3, 3)]
    b = b"II*\0" + struct.pack("<I", 8) + struct.pack("<H", len(tags))
    for tag, typ, value in tags:
        b += struct.pack("<HHII", tag, typ, 1, value)
    return (b + struct.pack("<I", 0)).ljust(210, b"\0")


with open("huge_header.tiff", "wb") as f:
    f.write(tiff_header(100000, 100000))
with open("not_a_tiff.tiff", "wb") as f:
    f.write(b"P5\n2 2\n255\n\0\0\0\0")
with open("huge_vertices.ply", "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
            b"property float x\nproperty float y\nproperty float z\nend_header\n")

# One star-shaped polygon of 1100 corners: assimp's triangulation is quadratic in the corners
# (a 32 000-corner polygon takes 20 s), so casmap rejects polygons above 1024 corners.
with open("polygon_1100.obj", "w") as f:
    corners = 1100
    for i in range(corners):
        a, r = 2 * math.pi * i / corners, (1.0 if i % 2 == 0 else 0.5)
        f.write(f"v {r * math.cos(a):.4f} {r * math.sin(a):.4f} 0\n")
    f.write("f " + " ".join(str(i + 1) for i in range(corners)) + "\n")
