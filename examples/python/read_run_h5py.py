"""Reading a run file without casmap: plain h5py (docs/run-file.md lists every dataset).

    python3 read_run_h5py.py RUN.h5
"""
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    scans = f["scans"]
    ranges = scans["ranges_m"][()]  # N x B float32, NaN where the beam has no range
    status = scans["status"][()]    # N x B uint8, 0 = ok
    angles = scans.attrs["start_angle_rad"] + np.arange(ranges.shape[1]) * scans.attrs[
        "angle_step_rad"]
    print(f"{ranges.shape[0]} scans, beams from {np.degrees(angles[0]):.1f} to "
          f"{np.degrees(angles[-1]):.1f} deg")
    print(f"ok beams: {np.count_nonzero(status == 0)}, median range "
          f"{np.nanmedian(ranges):.3f} m")
    if "labels" in scans:  # simulated: 0 valid, 1 mixed, 2 missing, 3 spike, 4 no target, 5 dazzled
        counts = np.bincount(scans["labels"][()].ravel(), minlength=6)
        print("labels valid/mixed/missing/spike/no_target/dazzled:", " ".join(map(str, counts)))
    if "poses" in f:
        xyz = f["poses/xyz_m"][()]  # P x 3, with f["poses/quat_xyzw"] the sensor pose
        print(f"{len(xyz)} poses, sensor travelled {np.linalg.norm(xyz[-1] - xyz[0]):.3f} m")
    if "maps/elevation_m" in f:
        print("elevation map", f["maps/elevation_m"].shape)
    # Format version 2: a fixed-length string dataset; version 1: a variable-length attribute.
    config = (f["config_yaml"][()].decode() if "config_yaml" in f
              else f.attrs.get("config_yaml", "-"))
    print("config:", config.splitlines()[0])
