"""Run files, mapping and (simulator builds) simulation, against the casmap program."""
import json

import numpy as np
import pytest

import casmap
from conftest import data_dir, run_cli

needs_sim = pytest.mark.skipif(not casmap.with_simulator, reason="robot build: no simulator")


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory, course4):
    """`casmap simulate` of course 4, test T, seed 1 (skipped without the program)."""
    import os
    exe = os.environ.get("CASMAP_EXE")
    if not exe or not casmap.with_simulator:
        pytest.skip("needs the casmap program with the simulator")
    path = tmp_path_factory.mktemp("run") / "cli.h5"
    run_cli(exe, "simulate", "--scene", course4, "--motion", "T", "--seed", 1, "--out", path)
    return path


@needs_sim
def test_simulate_equals_cli_byte_for_byte(cli_run, course4, tmp_path):
    run = casmap.simulate(casmap.load_scene(course4), "T", seed=1, threads=2)
    casmap.write_run(tmp_path / "py.h5", run)
    assert (tmp_path / "py.h5").read_bytes() == cli_run.read_bytes()


@needs_sim
def test_read_write_round_trip(cli_run, tmp_path):
    run = casmap.read_run(cli_run)
    n, b = run.scans.ranges_m.shape
    assert n > 100 and b == 181
    assert run.scans.labels.shape == (n, b) and run.seed == 1
    assert run.poses.xyz_m.shape[1] == 3 and run.maps.truth_m is not None
    ok = run.scans.status == 0
    assert np.all(np.isfinite(run.scans.ranges_m[ok])) and np.all(np.isnan(run.scans.ranges_m[~ok]))
    # Reading normalises the pose quaternions (io::ReadRunFile), so a copy may differ from the
    # simulator's file in their last bits (and so in its compressed bytes); the rest is exact.
    casmap.write_run(tmp_path / "copy.h5", run)
    copy = casmap.read_run(tmp_path / "copy.h5")
    for name in ("stamp_s", "raw", "status", "labels"):
        assert np.array_equal(getattr(copy.scans, name), getattr(run.scans, name))
    assert np.array_equal(copy.scans.ranges_m, run.scans.ranges_m, equal_nan=True)
    assert np.array_equal(copy.maps.truth_m, run.maps.truth_m)
    assert np.allclose(copy.poses.quat_xyzw, run.poses.quat_xyzw, rtol=0, atol=1e-15)
    assert copy.config_yaml == run.config_yaml and copy.seed == run.seed
    casmap.write_run(tmp_path / "again.h5", run)  # the same data, the same bytes
    assert (tmp_path / "again.h5").read_bytes() == (tmp_path / "copy.h5").read_bytes()


@needs_sim
def test_map_run_and_mapper_equal_casmap_map(exe, cli_run, tmp_path):
    run = casmap.read_run(cli_run)
    run_cli(exe, "map", cli_run, "--out", tmp_path / "maps")
    cli_h = casmap.read_map_tiff(tmp_path / "maps" / "elevation.tiff")
    cli_c = casmap.read_map_tiff(tmp_path / "maps" / "certainty.tiff")
    h, c, grid = casmap.map_run(run, grid=run.maps.grid)
    assert grid == run.maps.grid
    assert np.array_equal(h, cli_h) and np.array_equal(c, cli_c)
    # The same scans fed one at a time give the same maps (scan period: 1/75 s, the run's).
    mapper = casmap.Mapper(grid, scan_period_s=float(np.median(np.diff(run.scans.stamp_s))))
    s = run.scans
    for k in range(len(s.stamp_s)):
        mapper.add_scan(s.stamp_s[k], s.ranges_m[k], s.status[k], run.poses,
                        start_angle_rad=s.start_angle_rad, angle_step_rad=s.angle_step_rad,
                        beam_period_s=s.beam_period_s)
    assert np.array_equal(mapper.elevation, cli_h) and np.array_equal(mapper.certainty, cli_c)
    assert mapper.stats["beams_mapped"] > 0
    # The other mapper modes match `casmap map --mapper kalman --unknown nan` too.
    run_cli(exe, "map", cli_run, "--out", tmp_path / "kalman", "--mapper", "kalman",
            "--unknown", "nan")
    kh, kc, _ = casmap.map_run(run, grid=run.maps.grid, mapper="kalman", unknown="nan")
    assert np.array_equal(kh, casmap.read_map_tiff(tmp_path / "kalman" / "elevation.tiff"),
                          equal_nan=True)
    assert np.isnan(kh[kc == 0]).all()
    # The sweep-jump pre-filter needs whole runs: map_run gives what `casmap map` gives.
    run_cli(exe, "map", cli_run, "--out", tmp_path / "sweep", "--prefilter", "sweep_jump")
    sh, sc, _ = casmap.map_run(run, grid=run.maps.grid, prefilter="sweep_jump")
    assert np.array_equal(sh, casmap.read_map_tiff(tmp_path / "sweep" / "elevation.tiff"))
    assert np.array_equal(sc, casmap.read_map_tiff(tmp_path / "sweep" / "certainty.tiff"))
    # Course 4's box edges give it mixed pixels to reject: the maps differ from the plain ones.
    assert not np.array_equal(sc, c)
    # The consensus mode: `casmap map --mapper consensus`'s maps, the paper's certainty, and no
    # cell farther from 0 m than Eq. 6's (a mean never exceeds the largest |z|).
    run_cli(exe, "map", cli_run, "--out", tmp_path / "consensus", "--mapper", "consensus")
    ch, cc, _ = casmap.map_run(run, grid=run.maps.grid, mapper="consensus")
    assert np.array_equal(ch, casmap.read_map_tiff(tmp_path / "consensus" / "elevation.tiff"))
    assert np.array_equal(cc, c)
    assert (np.abs(ch) <= np.abs(h)).all() and (ch != h).any()
    with pytest.raises(ValueError, match="consensus"):
        casmap.map_run(run, grid=run.maps.grid, mapper="median")
    # ... and the scan-by-scan Mapper with the same (default) consensus settings.
    period = float(np.median(np.diff(run.scans.stamp_s)))
    incremental = casmap.Mapper(grid, scan_period_s=period, consensus_spread_m=0.02)
    for k in range(len(s.stamp_s)):
        incremental.add_scan(s.stamp_s[k], s.ranges_m[k], s.status[k], run.poses,
                             start_angle_rad=s.start_angle_rad, angle_step_rad=s.angle_step_rad,
                             beam_period_s=s.beam_period_s)
    assert np.array_equal(incremental.elevation, ch)
    assert np.array_equal(incremental.certainty, cc)
    for bad in ({"consensus_spread_m": -0.01}, {"consensus_spread_m": 0.02,
                                                 "consensus_min_hits": 1}):
        with pytest.raises(ValueError, match="consensus"):
            casmap.Mapper(grid, **bad)


@needs_sim
def test_scan_at_equals_casmap_scan(exe, course4):
    cli = json.loads(run_cli(exe, "scan", "--scene", course4, "--pose", "1,0,1,0,40,0",
                             "--seed", 3).stdout)
    scan = casmap.scan_at(casmap.load_scene(course4), (1, 0, 1, 0, 40, 0), seed=3)
    assert list(scan["raw"]) == cli["raw"]
    assert [casmap.BEAM_STATUS[s] for s in scan["status"]] == cli["status"]
    assert [casmap.BEAM_LABELS[v] for v in scan["labels"]] == cli["labels"]
    assert np.allclose(np.degrees(scan["angles_rad"]), cli["angles_deg"], atol=1e-5)


@needs_sim
def test_truth_equals_casmap_truth(exe, course4, tmp_path):
    run_cli(exe, "truth", "--scene", course4, "--grid", "1,-1,0.025,200,80", "--out",
            tmp_path / "t.tiff")
    grid = casmap.Grid(x0_m=1, y0_m=-1, cell_m=0.025, rows=200, cols=80)
    t = casmap.truth(casmap.load_scene(course4), grid)
    assert t.shape == (200, 80) and t.max() > 0.0
    assert np.array_equal(t, casmap.read_map_tiff(tmp_path / "t.tiff"))


@needs_sim
def test_bad_seed_and_threads_are_value_errors(course4):
    scene = casmap.load_scene(course4)
    grid = casmap.Grid(x0_m=1, y0_m=-1, cell_m=0.025, rows=4, cols=4)
    # A negative seed was a pybind11 TypeError; threads=-1 or 5000 passed unchecked.
    for kwargs, field in (({"seed": -1}, "seed"), ({"seed": 2**64}, "seed"),
                          ({"seed": 1.5}, "seed"), ({"threads": -1}, "threads"),
                          ({"threads": 5000}, "threads"), ({"threads": True}, "threads")):
        with pytest.raises(ValueError, match=rf"^{field} = "):
            casmap.simulate(scene, "T", **kwargs)
    with pytest.raises(ValueError, match=r"^seed = -3 \(allowed: an integer 0..2\*\*64-1\)"):
        casmap.scan_at(scene, (1, 0, 1, 0, 40, 0), seed=-3)
    with pytest.raises(ValueError, match=r"^threads = -2 \(allowed: 0 \(all cores\) or 1..1024"):
        casmap.truth(scene, grid, threads=-2)
    assert casmap.truth(scene, grid, threads=np.int64(2)).shape == (4, 4)


def test_map_run_names_a_bad_cell_size(cli_run):
    run = casmap.read_run(cli_run)
    # cell_m = 0 used to be reported as "grid: x0_m/y0_m (must be finite)".
    for cell in (0.0, -0.025, float("nan")):
        with pytest.raises(ValueError, match=r"^run: cell_m = .* \(must be a finite number > 0\)"):
            casmap.map_run(run, cell_m=cell)


def test_bad_run_file_raises_the_cli_message(exe, tmp_path):
    bad = tmp_path / "bad.h5"
    bad.write_bytes(b"not hdf5")
    cli = run_cli(exe, "map", bad, check=False)
    assert cli.returncode == 2
    with pytest.raises(ValueError) as err:
        casmap.read_run(bad)
    assert cli.stderr.strip() == "casmap: " + str(err.value)


def test_write_and_read_a_recorded_style_run(tmp_path):
    """A run without truth or maps (what `casmap record` writes), built in numpy."""
    n, b = 4, 181
    ranges = np.full((n, b), 2.0, np.float32)
    status = np.zeros((n, b), np.uint8)
    status[:, 0] = 1
    ranges[:, 0] = np.nan
    scans = casmap.Scans(stamp_s=np.arange(n) / 75.0, ranges_m=ranges,
                         raw=np.where(status == 0, 2000, 8191).astype(np.uint16), status=status,
                         start_angle_rad=-np.pi / 2, angle_step_rad=np.pi / 180,
                         beam_period_s=casmap.LMS200_BEAM_PERIOD_S)
    poses = casmap.Poses(stamp_s=np.array([0.0, 1.0]), xyz_m=np.array([[0, 0, 1], [1, 0, 1.0]]),
                         quat_xyzw=np.array([[0, 0, 0, 1], [0, 0, 0, 1.0]]))
    casmap.write_run(tmp_path / "r.h5", casmap.Run(scans=scans, poses=poses))
    back = casmap.read_run(tmp_path / "r.h5")
    assert back.scans.labels is None and back.seed is None and back.maps.elevation_m is None
    assert np.array_equal(back.scans.raw, scans.raw)
    assert np.array_equal(back.scans.ranges_m, ranges, equal_nan=True)
    assert np.array_equal(back.poses.xyz_m, poses.xyz_m)
    with pytest.raises(ValueError, match="scans.status"):
        bad = casmap.Scans(**{**scans.__dict__, "status": status[:, :10]})
        casmap.write_run(tmp_path / "x.h5", casmap.Run(scans=bad, poses=poses))


@needs_sim
def test_stage_params_and_streamed_prefilter_equal_casmap_map(exe, cli_run, tmp_path):
    run = casmap.read_run(cli_run)
    grid, s = run.maps.grid, run.scans
    period = float(np.median(np.diff(s.stamp_s)))
    # params: `casmap map --set`'s names; the maps equal the program's with the same --set.
    run_cli(exe, "map", cli_run, "--out", tmp_path / "sj", "--prefilter", "sweep_jump",
            "--set", "sweep_jump.margin_m=0.03", "--set", "sweep_jump.max_angle_deg=5")
    params = {"sweep_jump.margin_m": 0.03, "sweep_jump.max_angle_deg": 5}
    h, c, _ = casmap.map_run(run, grid=grid, prefilter="sweep_jump", params=params)
    assert np.array_equal(h, casmap.read_map_tiff(tmp_path / "sj" / "elevation.tiff"))
    assert np.array_equal(c, casmap.read_map_tiff(tmp_path / "sj" / "certainty.tiff"))
    default_h, _, _ = casmap.map_run(run, grid=grid, prefilter="sweep_jump")
    assert not np.array_equal(h, default_h)  # the parameters were applied
    run_cli(exe, "map", cli_run, "--out", tmp_path / "cs", "--mapper", "consensus",
            "--set", "consensus.spread_m=0.05")
    ch, _, _ = casmap.map_run(run, grid=grid, mapper="consensus",
                              params={"consensus.spread_m": 0.05})
    assert np.array_equal(ch, casmap.read_map_tiff(tmp_path / "cs" / "elevation.tiff"))
    # The scan-by-scan Mapper with the same pre-filter holds one scan back (reach 1) and, once
    # finished, gives map_run's maps bit for bit, with every rejection counted.
    mapper = casmap.Mapper(grid, scan_period_s=period, mapper="consensus",
                           prefilter="sweep_jump", params=params)
    for k in range(len(s.stamp_s)):
        mapper.add_scan(s.stamp_s[k], s.ranges_m[k], s.status[k], run.poses,
                        start_angle_rad=s.start_angle_rad, angle_step_rad=s.angle_step_rad,
                        beam_period_s=s.beam_period_s)
        assert mapper.waiting == 1
    mapper.finish()
    assert mapper.waiting == 0
    both_h, both_c, _ = casmap.map_run(run, grid=grid, mapper="consensus",
                                       prefilter="sweep_jump", params=params)
    assert np.array_equal(mapper.elevation, both_h)
    assert np.array_equal(mapper.certainty, both_c)
    assert mapper.stats["beams_rejected"] > 0
    with pytest.raises(ValueError, match="after Finish"):
        mapper.add_scan(s.stamp_s[0], s.ranges_m[0], s.status[0], run.poses)
    # Bad input: ValueError naming the parameter or the rule.
    with pytest.raises(ValueError, match="pre-filter is none"):
        casmap.map_run(run, grid=grid, params={"sweep_jump.margin_m": 0.03})
    with pytest.raises(ValueError, match="sweep_jump.margin_m"):
        casmap.Mapper(grid, prefilter="sweep_jump", params={"sweep_jump.margin_m": -1})
    with pytest.raises(ValueError, match="consensus_spread_m"):
        casmap.Mapper(grid, mapper="kalman", consensus_spread_m=0.02)
    with pytest.raises(ValueError, match="params"):
        casmap.map_run(run, grid=grid, params=[("sweep_jump.margin_m", 0.03)])
