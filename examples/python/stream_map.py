"""Map a run scan by scan, as a program fed by a scanner would: the consensus cell height and
the sweep-jump pre-filter, each scan mapped once the next one has arrived. Checks the result
against the whole-run map_run and prints how many beams the pre-filter rejected.

    python3 stream_map.py RUN.h5 [MARGIN_M]
"""
import sys

import numpy as np

import casmap

run = casmap.read_run(sys.argv[1])  # ValueError naming the dataset if the file is bad
margin_m = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
params = {"sweep_jump.margin_m": margin_m, "consensus.spread_m": 0.05}
scans = run.scans
grid = run.maps.grid if run.maps.grid is not None else casmap.map_run(run)[2]
period = float(np.median(np.diff(scans.stamp_s)))

mapper = casmap.Mapper(grid, scan_period_s=period, mapper="consensus", prefilter="sweep_jump",
                       params=params)
for k in range(len(scans.stamp_s)):
    # A scanner delivers scan k now; the mapper maps scan k - 1 (its next neighbour arrived).
    mapper.add_scan(scans.stamp_s[k], scans.ranges_m[k], scans.status[k], run.poses,
                    start_angle_rad=scans.start_angle_rad, angle_step_rad=scans.angle_step_rad,
                    beam_period_s=scans.beam_period_s)
print(f"{len(scans.stamp_s)} scans added, {mapper.waiting} waiting for its neighbour")
mapper.finish()  # the last scan, without a later neighbour

whole, _, _ = casmap.map_run(run, grid=grid, mapper="consensus", prefilter="sweep_jump",
                             params=params)
same = np.array_equal(mapper.elevation, whole, equal_nan=True)
stats = mapper.stats
print(f"beams mapped {stats['beams_mapped']}, rejected by sweep_jump {stats['beams_rejected']}; "
      f"equal to map_run: {same}")
sys.exit(0 if same else 1)
