"""Shared fixtures: the casmap program (CASMAP_EXE, set by ctest and scripts/test-package.sh),
the data directory (CASMAP_DATA_DIR or the source tree) and a simulated run of course 4."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import casmap

HERE = pathlib.Path(__file__).resolve().parent


def data_dir() -> pathlib.Path:
    """scenes/ and config/: $CASMAP_DATA_DIR (an install's share/casmap) or the source tree."""
    env = os.environ.get("CASMAP_DATA_DIR")
    return pathlib.Path(env) if env else HERE.parent.parent


@pytest.fixture(scope="session")
def exe():
    path = os.environ.get("CASMAP_EXE")
    if not path:
        pytest.skip("CASMAP_EXE not set: no casmap program to compare with")
    return path


def run_cli(exe, *args, check=True):
    """Runs `casmap ARGS`; returns the CompletedProcess (text)."""
    result = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"casmap {' '.join(map(str, args))}: {result.stderr}")
    return result


@pytest.fixture(scope="session")
def course4():
    return data_dir() / "scenes" / "courses" / "course04.yaml"


@pytest.fixture()
def maps_pair(tmp_path):
    """A 60 x 40 elevation map with steps, spikes and holes, and its certainty; also as TIFFs."""
    rng = np.random.default_rng(7)
    h = np.zeros((60, 40), np.float32)
    h[20:35, 10:25] = 0.12
    h += rng.normal(0.0, 0.004, h.shape).astype(np.float32)
    c = np.full(h.shape, 6.0, np.float32)
    holes = rng.random(h.shape) < 0.08
    h[holes], c[holes] = 0.0, 0.0
    spikes = rng.random(h.shape) < 0.02
    h[spikes] += 0.3
    c[spikes] = 3.0
    casmap.write_map_tiff(tmp_path / "h.tiff", h)
    casmap.write_map_tiff(tmp_path / "c.tiff", c)
    return h, c, tmp_path / "h.tiff", tmp_path / "c.tiff"
