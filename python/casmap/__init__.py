"""casmap: a SICK LMS 200 simulator, terrain mapper (Eq. 1-6) and the CAS filter of Ye &
Borenstein, from Python. numpy in, numpy out; maps are float32 arrays with rows along-track.

    import casmap
    filtered, classes = casmap.filter("cas", elevation, certainty, k=2)
    pi = casmap.performance_index(filtered, raw, truth)

Bad input raises ValueError with the library's one-line message (the `casmap` program prints
the same, naming its flags, e.g. --set, where the library names its settings). Long calls
(filtering, mapping, simulating, reading and writing run files) release the GIL.
See docs/api/python.md.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _casmap
from ._casmap import (Grid, cas_classes_percent, performance_index, read_map_tiff,
                      with_simulator, write_map_tiff)

__all__ = [
    "Grid", "Mapper", "Poses", "Run", "Scans", "Maps", "filter", "performance_index",
    "cas_classes_percent", "read_run", "write_run", "map_run", "read_map_tiff",
    "write_map_tiff", "with_simulator", "BEAM_STATUS", "BEAM_LABELS", "CAS_CLASSES",
    "FILTER_METHODS", "ALL_FILTER_METHODS", "LMS200_BEAM_PERIOD_S",
]

#: Filter methods of the paper's benchmark, in its order.
FILTER_METHODS = ("cas", "wiener", "average", "median", "cwm")
#: Every method casmap.filter and `casmap filter --method` take: the paper's five, then the
#: CAS variants (docs/commands/filter.md), which return classes like "cas".
ALL_FILTER_METHODS = FILTER_METHODS + ("cas_terrain", "cas_trail", "cas_median", "cas_edge",
                                       "cas_hybrid")
#: core::BeamStatus codes (the `status` arrays).
BEAM_STATUS = ("ok", "no_return", "dazzle", "overflow", "low_signal", "read_error",
               "out_of_range")
#: core::BeamLabel codes (the `labels` arrays of simulated scans).
BEAM_LABELS = ("valid", "mixed", "missing", "spike", "no_target", "dazzled")
#: mapper::PixelClass codes (the `classes` array of casmap.filter("cas", ...)).
CAS_CLASSES = ("untouched", "removed", "filled", "border")
#: Seconds between adjacent 1-degree pulses of the LMS 200 (75 Hz mirror): (1/75) / 360.
LMS200_BEAM_PERIOD_S = (1.0 / 75.0) / 360.0


def _whole_number(name: str, value, low: int, high: int, allowed: str) -> int:
    """`value` as an int in low..high; ValueError "name = value (allowed: ...)" otherwise (a
    negative seed used to be a pybind11 TypeError, a thread count of -1 passed unchecked)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) \
            or not low <= int(value) <= high:
        raise ValueError(f"{name} = {value!r} (allowed: {allowed})")
    return int(value)


def _seed(seed) -> int:
    return _whole_number("seed", seed, 0, 2**64 - 1, "an integer 0..2**64-1")


def _threads(threads) -> int:
    return _whole_number("threads", threads, 0, 1024, "0 (all cores) or 1..1024, as --threads")


def _param_text(name: str, value) -> str:
    """A keyword value as `casmap filter --set NAME=VALUE` spells it."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back as the same double
    return str(value)


def filter(method: str, elevation, certainty=None, **params):
    """Runs one filter on an elevation map (float32, metres), as `casmap filter`.

    method: the paper's "cas", "wiener", "average", "median" or "cwm", or a CAS variant
    (ALL_FILTER_METHODS). certainty (float32 counts) is required by the CAS methods. params:
    the names of `casmap filter --set`, e.g. k=2, A=12.0, gs_mode="variance", e_term=True,
    window=5. Returns (filtered, classes): classes is the per-pixel uint8 array of
    CAS_CLASSES codes (for every CAS method, as the CLI's OUT_classes.tiff), None for the
    baselines.
    """
    pairs = [(name, _param_text(name, value)) for name, value in params.items()]
    return _casmap._filter(method, elevation, certainty, pairs)


@dataclass
class Scans:
    """/scans of a run file: N scans of B beams sharing one geometry."""
    stamp_s: np.ndarray                 # (N,) float64, time of beam 0
    ranges_m: np.ndarray                # (N, B) float32, NaN where status != ok
    raw: np.ndarray                     # (N, B) uint16, the value the scanner sent
    status: np.ndarray                  # (N, B) uint8, BEAM_STATUS codes
    start_angle_rad: float              # beam i at start + i * step about sensor +z
    angle_step_rad: float
    beam_period_s: float                # beam i measured at stamp + i * beam_period_s
    labels: Optional[np.ndarray] = None        # (N, B) uint8 BEAM_LABELS (simulated runs)
    true_range_m: Optional[np.ndarray] = None  # (N, B) float32 (simulated runs)
    beam_time_offset_s: Optional[np.ndarray] = None  # (B,) replaces i * beam_period_s

    @property
    def angles_rad(self) -> np.ndarray:
        return self.start_angle_rad + np.arange(self.ranges_m.shape[1]) * self.angle_step_rad


@dataclass
class Poses:
    """/poses: world_T_sensor samples, strictly increasing stamps."""
    stamp_s: np.ndarray    # (P,) float64
    xyz_m: np.ndarray      # (P, 3) float64, sensor origin in the world
    quat_xyzw: np.ndarray  # (P, 4) float64, unit quaternion world_R_sensor
    _trajectory: object = field(default=None, repr=False, compare=False)

    def trajectory(self):
        """The C++ trajectory, built once (ValueError for bad stamps or shapes)."""
        if self._trajectory is None:
            self._trajectory = _casmap._Trajectory(self.stamp_s, self.xyz_m, self.quat_xyzw)
        return self._trajectory

    @staticmethod
    def empty() -> "Poses":
        return Poses(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 4)))


@dataclass
class Maps:
    """/maps: layers on one grid (None when absent)."""
    grid: Optional[Grid] = None
    elevation_m: Optional[np.ndarray] = None
    certainty: Optional[np.ndarray] = None
    truth_m: Optional[np.ndarray] = None
    filtered: dict = field(default_factory=dict)  # method -> float32 map


@dataclass
class Run:
    """Everything a run file holds (docs/run-file.md)."""
    scans: Scans
    poses: Poses
    maps: Maps = field(default_factory=Maps)
    seed: Optional[int] = None
    config_yaml: str = ""
    format: Optional[tuple] = None  # ("8m"|"16m"|"32m", "mm"|"cm") when known

    @staticmethod
    def _from_dict(d: dict) -> "Run":
        return Run(scans=Scans(**d["scans"]), poses=Poses(**d["poses"]), maps=Maps(**d["maps"]),
                   seed=d["seed"], config_yaml=d["config_yaml"], format=d["format"])

    def _to_dict(self) -> dict:
        scans = {k: getattr(self.scans, k) for k in (
            "stamp_s", "ranges_m", "raw", "status", "labels", "true_range_m",
            "start_angle_rad", "angle_step_rad", "beam_period_s", "beam_time_offset_s")}
        poses = {"stamp_s": self.poses.stamp_s, "xyz_m": self.poses.xyz_m,
                 "quat_xyzw": self.poses.quat_xyzw}
        maps = {"grid": self.maps.grid, "elevation_m": self.maps.elevation_m,
                "certainty": self.maps.certainty, "truth_m": self.maps.truth_m,
                "filtered": dict(self.maps.filtered)}
        return {"scans": scans, "poses": poses, "maps": maps, "seed": self.seed,
                "config_yaml": self.config_yaml, "format": self.format}


def read_run(path) -> Run:
    """Reads and validates a run file (`casmap simulate` / `casmap record` output)."""
    return Run._from_dict(_casmap._read_run(os.fspath(path)))


def write_run(path, run: Run) -> None:
    """Writes `run` to `path` atomically; the same data gives a byte-identical file."""
    _casmap._write_run(os.fspath(path), run._to_dict())


def _stage_sets(params) -> list:
    """{"sweep_jump.margin_m": 0.04, ...} -> ["sweep_jump.margin_m=0.04", ...] (`--set` texts)."""
    if params is None:
        return []
    if not isinstance(params, dict):
        raise ValueError(f"params = {params!r} (a dict of mapping-stage parameters, e.g. "
                         "{'sweep_jump.margin_m': 0.04})")
    return [f"{name}={_param_text(name, value)}" for name, value in params.items()]


def map_run(run: Run, grid: Optional[Grid] = None, cell_m: float = 0.025, a: int = 3,
            delta_l_m: float = 0.032, mapper: str = "paper", unknown: str = "zero",
            prefilter: str = "none", params: Optional[dict] = None):
    """Elevation and certainty maps of a run, as `casmap map` builds them.

    mapper "paper" (Eq. 1-6), "kalman" or "consensus"; unknown "zero" (the paper) or "nan"; prefilter
    "none", "shadow", "range_jump" or "sweep_jump" (as `casmap map --mapper/--unknown/--prefilter`).
    params: the mapping stages' parameters by `casmap map --set`'s names, e.g.
    {"sweep_jump.margin_m": 0.04, "consensus.spread_m": 0.05}; a stage the call does not run
    is a ValueError, as in `casmap map`.
    grid None: the smallest grid of cell_m cells covering every valid beam. Returns
    (elevation, certainty, grid).
    """
    d = _casmap._map_scans(run._to_dict(), grid, cell_m, a, delta_l_m, mapper, unknown,
                           prefilter, _stage_sets(params))
    return d["elevation"], d["certainty"], d["grid"]


class Mapper:
    """The terrain mapper fed scan by scan, e.g. from a live scanner: `map_run`'s mapper modes,
    unknown conventions, pre-filters and params, one scan at a time.

        mapper = casmap.Mapper(casmap.Grid(x0_m=1, y0_m=-1, cell_m=0.025, rows=200, cols=80))
        mapper.add_scan(stamp_s, ranges_m, status, poses)
        mapper.finish()
        h, c = mapper.elevation, mapper.certainty

    consensus_spread_m (None: the paper's Eq. 6) selects the consensus cell height, as
    `casmap map --mapper consensus --set consensus.spread_m=...`: a cell whose heights all lie
    within that spread, over at least consensus_min_hits points, holds their mean.
    prefilter "sweep_jump" compares each scan with the next one(s) (sweep_jump.reach), so a scan
    is mapped when they have arrived and finish() maps the last; `waiting` counts the scans held
    back. After finish() the maps equal map_run's on the same scans when scan_period_s is the
    run's. ValueError for a bad value, naming the field.
    """

    def __init__(self, grid: Grid, a: int = 3, delta_l_m: float = 0.032,
                 scan_period_s: float = 1.0 / 75.0, *, mapper: Optional[str] = None,
                 unknown: str = "zero", prefilter: str = "none",
                 consensus_spread_m: float | None = None, consensus_min_hits: int = 2,
                 params: Optional[dict] = None):
        if mapper is None:
            mapper = "paper" if consensus_spread_m is None else "consensus"
        self._mapper = _casmap._Mapper(grid, a, delta_l_m, scan_period_s, mapper, unknown,
                                       prefilter, consensus_spread_m, consensus_min_hits,
                                       _stage_sets(params))

    def add_scan(self, stamp_s: float, ranges_m, status, poses: Poses, *,
                 start_angle_rad: float = -math.pi / 2, angle_step_rad: float = math.pi / 180,
                 beam_period_s: float = LMS200_BEAM_PERIOD_S, beam_time_offset_s=None) -> None:
        """Maps one scan: ranges_m float32 (B,), status uint8 (B,) BEAM_STATUS codes, beam i
        at start_angle_rad + i * angle_step_rad measured at stamp_s + i * beam_period_s, each
        beam placed with the pose of `poses` at its own time (beams without one are skipped).
        The defaults are the LMS 200's 180 deg / 1 deg scan."""
        offsets = [] if beam_time_offset_s is None else list(map(float, beam_time_offset_s))
        geometry = _casmap._ScanGeometry(start_angle_rad, angle_step_rad, beam_period_s, offsets)
        self._mapper.add_scan(stamp_s, ranges_m, status, poses.trajectory(), geometry)

    def finish(self) -> None:
        """No more scans: maps the ones the sweep_jump pre-filter still holds back. A later
        add_scan is a ValueError."""
        self._mapper.finish()

    @property
    def waiting(self) -> int:
        """Scans added but not yet mapped (sweep_jump: up to its reach; 0 after finish())."""
        return self._mapper.waiting

    @property
    def elevation(self) -> np.ndarray:
        """H (m), float32 (rows, cols); 0 where never observed."""
        return self._mapper.elevation

    @property
    def certainty(self) -> np.ndarray:
        """C (counts), float32 (rows, cols); 0 where never observed."""
        return self._mapper.certainty

    @property
    def grid(self) -> Grid:
        return self._mapper.grid

    @property
    def stats(self) -> dict:
        """beams_seen, beams_not_ok, beams_rejected (by the pre-filter), beams_no_pose,
        beams_outside, beams_mapped."""
        return self._mapper.stats


if with_simulator:
    from ._casmap import Scene, load_scene

    __all__ += ["Scene", "load_scene", "scan_at", "simulate", "truth"]

    def scan_at(scene, pose, seed: int = 0, sensor=None, ideal: bool = False) -> dict:
        """One simulated LMS 200 scan from a fixed pose, as `casmap scan`.

        pose: (x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg), world frame. sensor: an LMS 200
        YAML file (config/lms200.yaml) or None for the defaults. Returns a dict of arrays:
        angles_rad, ranges_m (float32), raw (uint16), status (BEAM_STATUS codes), labels
        (BEAM_LABELS codes), true_range_m.
        """
        return _casmap._scan_at(scene, [float(v) for v in pose], _seed(seed),
                                None if sensor is None else os.fspath(sensor), ideal)

    def simulate(scene, motion: str, seed: int = 1, rig=None, sensor=None,
                 speed_m_s: Optional[float] = None, threads: int = 0) -> Run:
        """One simulated run, as `casmap simulate`: motion T, TR, TP, TRP (the table) or
        vehicle; rig and sensor are YAML files (None: the defaults). The result, written
        with write_run, is byte-identical to the CLI's run file; any thread count gives the
        same run."""
        d = _casmap._simulate(scene, motion, _seed(seed),
                              None if rig is None else os.fspath(rig),
                              None if sensor is None else os.fspath(sensor), speed_m_s,
                              _threads(threads))
        return Run._from_dict(d)

    def truth(scene, grid: Grid, threads: int = 0) -> np.ndarray:
        """The exact ground-truth elevation (m, float32) of every cell of `grid`: the highest
        surface point in the cell (as `casmap truth`). Any thread count gives the same map."""
        return _casmap.truth(scene, grid, _threads(threads))
