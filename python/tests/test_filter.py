"""casmap.filter, performance_index, cas_classes_percent against `casmap filter`."""
import concurrent.futures

import numpy as np
import pytest

import casmap
from conftest import run_cli


@pytest.mark.parametrize("method", casmap.ALL_FILTER_METHODS)
def test_filter_equals_cli_bit_for_bit(exe, maps_pair, tmp_path, method):
    h, c, h_tiff, c_tiff = maps_pair
    out = tmp_path / f"{method}.tiff"
    run_cli(exe, "filter", "--method", method, "--elevation", h_tiff, "--certainty", c_tiff,
            "--set", "window=5", "--out", out)
    filtered, classes = casmap.filter(method, h, c, window=5)
    assert filtered.dtype == np.float32 and filtered.shape == h.shape
    assert np.array_equal(filtered, casmap.read_map_tiff(out), equal_nan=True)
    classes_tiff = tmp_path / f"{method}_classes.tiff"
    if method.startswith("cas"):  # every CAS method writes classes, and returns them
        assert classes is not None and classes.dtype == np.uint8
        assert np.array_equal(classes.astype(np.float32), casmap.read_map_tiff(classes_tiff))
    else:
        assert classes is None and not classes_tiff.exists()


def test_cas_parameters_by_set_names(exe, maps_pair, tmp_path):
    h, c, h_tiff, c_tiff = maps_pair
    out = tmp_path / "cas.tiff"
    run_cli(exe, "filter", "--method", "cas", "--elevation", h_tiff, "--certainty", c_tiff,
            "--set", "k=3", "--set", "A=4.5", "--set", "gs_mode=variance", "--set", "e_term=on",
            "--out", out)
    filtered, _ = casmap.filter("cas", h, c, k=3, A=4.5, gs_mode="variance", e_term=True)
    assert np.array_equal(filtered, casmap.read_map_tiff(out))
    default, _ = casmap.filter("cas", h, c)
    assert not np.array_equal(filtered, default)  # the parameters did reach the filter


def test_classes_percent(maps_pair):
    h, c, _, _ = maps_pair
    _, classes = casmap.filter("cas", h, c, k=2)
    assert set(np.unique(classes)) <= {0, 1, 2, 3}
    shares = casmap.cas_classes_percent(classes, c)
    assert shares["cells"] == (60 - 4) * (40 - 4)  # the border of k = 2 is not processed
    total = shares["removed"] + shares["filled"] + shares["untouched"]
    assert total == pytest.approx(100.0)
    assert shares["filled"] > 0 and shares["removed"] > 0  # the holes and spikes
    assert shares["observed"]["cells"] <= shares["cells"]


def test_performance_index():
    truth = np.zeros((220, 100), np.float32)
    raw = truth.copy()
    raw[100, 50] = 1.0
    half = raw * np.float32(0.5)
    assert casmap.performance_index(raw, raw, truth) == 1.0
    assert casmap.performance_index(truth, raw, truth) == 0.0
    assert casmap.performance_index(half, raw, truth) == pytest.approx(0.25)
    # The paper's region is the centred 200 x 80: a difference outside it does not count.
    raw[0, 0] = 5.0
    assert casmap.performance_index(half, raw, truth) == pytest.approx(0.25)
    assert casmap.performance_index(half, raw, truth, region="full") < 0.25


def test_errors_are_the_cli_messages(exe, maps_pair, tmp_path):
    h, c, h_tiff, c_tiff = maps_pair
    cli = run_cli(exe, "filter", "--method", "cas", "--elevation", h_tiff, "--certainty",
                  c_tiff, "--set", "k=9", "--out", tmp_path / "x.tiff", check=False)
    assert cli.returncode == 2
    with pytest.raises(ValueError) as err:
        casmap.filter("cas", h, c, k=9)
    # The library names the parameter (the keyword k); the CLI shows where it came from as its
    # flag, --set: the same field, value and rule.
    assert str(err.value) == "filter parameters: k = 9 (allowed: integer 1..7)"
    assert cli.stderr.strip() == "casmap: --set: k = 9 (allowed: integer 1..7)"

    not_tiff = tmp_path / "not.tiff"
    not_tiff.write_text("hello")
    cli = run_cli(exe, "filter", "--method", "median", "--elevation", not_tiff, "--out",
                  tmp_path / "y.tiff", check=False)
    with pytest.raises(ValueError) as err:
        casmap.read_map_tiff(not_tiff)
    assert cli.stderr.strip() == "casmap: " + str(err.value)


def test_rejects_what_it_would_have_to_convert(maps_pair):
    h, c, _, _ = maps_pair
    with pytest.raises(ValueError, match="float32"):
        casmap.filter("median", h.astype(np.float64))
    with pytest.raises(ValueError, match="required for method cas"):
        casmap.filter("cas", h)
    with pytest.raises(ValueError, match="unknown filter parameter"):
        casmap.filter("median", h, windoww=3)
    nan = h.copy()
    nan[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"pixel \(row 3, col 4\)"):
        casmap.filter("median", nan)
    # A non-contiguous float32 view is fine (copied, not converted).
    filtered, _ = casmap.filter("median", h[:, ::2])
    assert np.array_equal(filtered, casmap.filter("median", np.ascontiguousarray(h[:, ::2]))[0])


def test_threads_give_the_same_maps(maps_pair):
    h, c, _, _ = maps_pair
    expected = [casmap.filter(m, h, c)[0] for m in casmap.FILTER_METHODS]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda m: casmap.filter(m, h, c)[0], casmap.FILTER_METHODS * 2))
    for i, g in enumerate(got):
        assert np.array_equal(g, expected[i % len(expected)])


def test_bad_arguments_are_value_errors_naming_them(maps_pair):
    h, c, _, _ = maps_pair
    # A region that is neither None, 'full' nor 4 integers was a pybind11 RuntimeError.
    for region in ("centre", (0.5, 0, 10, 10), object()):
        with pytest.raises(ValueError, match=r"^region = .*\(must be None"):
            casmap.performance_index(h, h, h, region=region)
    with pytest.raises(ValueError, match=r"^region = 3 numbers"):
        casmap.performance_index(h, h, h, region=(0, 0, 10))
    # A class code beyond CAS_CLASSES was counted as untouched.
    _, classes = casmap.filter("cas", h, c)
    classes[5, 7] = 9
    with pytest.raises(ValueError, match=r"^classes: pixel \(row 5, col 7\) = 9 \(allowed: 0..3"):
        casmap.cas_classes_percent(classes)

