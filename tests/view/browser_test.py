#!/usr/bin/python3
"""Browser tests of `casmap view` in headless Chromium (Debian: chromium, chromium-driver,
python3-selenium). Each test serves one folder with `casmap view DIR --port 0`, opens the page
and checks what a person would read off it against the files the page was made from:

  bench    the PI table's rows equal bench.json; the value under the pointer equals the TIFF's
  sweep    the heat map's clicked cell shows that point's parameters from sweep.json
  dataset  the manifest table has one row per line; a sample's value under the pointer equals
           the run file's map
  live     the scan count on the page increases while status.json is rewritten

Usage: browser_test.py --casmap BUILD/apps/casmap/casmap --out OUTDIR
       [--bench DIR] [--sweep DIR] [--dataset DIR] [--live DIR]
Each test saves a screenshot OUTDIR/<test>.png. Exit status 0 when all given tests pass.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import cv2
import h5py
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.actions.action_builder import ActionBuilder
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--disable-dev-shm-usage", "--window-size=1500,1100"]


class View:
    """`casmap view DIR --port 0` in the background; .url once it listens."""

    def __init__(self, casmap, folder):
        self.proc = subprocess.Popen([casmap, "view", folder, "--port", "0"],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        if " at http://" not in line:
            self.proc.kill()
            raise AssertionError("casmap view did not start: %r %r"
                                 % (line, self.proc.stderr.read()))
        self.url = line.split(" at ")[1].split()[0]

    def close(self):
        self.proc.terminate()
        self.proc.wait(timeout=10)


def make_driver(profile):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in CHROMIUM_FLAGS + ["--user-data-dir=" + profile]:
        options.add_argument(flag)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def open_page(driver, url):
    driver.get(url)
    WebDriverWait(driver, 30).until(
        lambda d: d.find_element(By.TAG_NAME, "body").get_attribute("data-ready") in
        ("true", "error"))
    state = driver.find_element(By.TAG_NAME, "body").get_attribute("data-ready")
    assert state == "true", driver.find_element(By.ID, "main").text


def point_at_cell(driver, layer, row, col):
    """Moves the pointer over cell (row, col) of the panel showing `layer`."""
    canvas = driver.find_element(By.CSS_SELECTOR, 'canvas[data-layer="%s"]' % layer)
    driver.execute_script("arguments[0].parentElement.scrollIntoView({block: 'center'});"
                          "arguments[0].parentElement.scrollTop = 0;"
                          "arguments[0].parentElement.scrollLeft = 0;", canvas)
    zoom = int(driver.find_element(By.ID, "zoom-label").get_attribute("data-zoom"))
    rect = driver.execute_script("return arguments[0].getBoundingClientRect().toJSON();", canvas)
    x = rect["left"] + (col + 0.5) * zoom
    y = rect["top"] + (row + 0.5) * zoom
    actions = ActionBuilder(driver)
    actions.pointer_action.move_to_location(int(x), int(y))
    actions.perform()
    WebDriverWait(driver, 5).until(lambda d: d.find_elements(
        By.CSS_SELECTOR, '#cell-info [data-field="row"]'))


def info_value(driver, selector):
    return driver.find_element(By.CSS_SELECTOR, "#cell-info " + selector).get_attribute(
        "data-value")


def same_float(page_text, expected):
    value = float(page_text)
    if math.isnan(expected):
        return math.isnan(value)
    return value == float(expected)


def visible_cells(driver, layer):
    """Rows and cols of the panel's top-left corner visible without scrolling."""
    canvas = driver.find_element(By.CSS_SELECTOR, 'canvas[data-layer="%s"]' % layer)
    frame = driver.execute_script("return arguments[0].parentElement.getBoundingClientRect()"
                                  ".toJSON();", canvas)
    zoom = int(driver.find_element(By.ID, "zoom-label").get_attribute("data-zoom"))
    return int(frame["height"] // zoom) - 1, int(frame["width"] // zoom) - 1


def pick_cell(maps, rows, cols):
    """The cell in [0, rows) x [0, cols) where the first map is highest (most telling)."""
    best = (0, 0)
    first = maps[0]
    for r in range(min(rows, first.shape[0])):
        for c in range(min(cols, first.shape[1])):
            v = first[r, c]
            if not math.isnan(v) and (math.isnan(first[best]) or v > first[best]):
                best = (r, c)
    return best


def test_bench(driver, casmap, folder, out):
    with open(os.path.join(folder, "bench.json")) as f:
        bench = json.load(f)
    view = View(casmap, folder)
    try:
        open_page(driver, view.url)
        rows = driver.find_elements(By.CSS_SELECTOR, "#pi-table tbody tr")
        assert len(rows) == len(bench["runs"]), (len(rows), len(bench["runs"]))
        by_key = {"course%02d_%s" % (r["course"], r["test"]): r for r in bench["runs"]}
        for tr in rows:
            run = by_key[tr.get_attribute("data-key")]
            cells = {td.get_attribute("data-col"): td for td in tr.find_elements(By.TAG_NAME, "td")}
            assert int(cells["course"].text) == run["course"]
            assert cells["test"].text == run["test"]
            for name, score in run["filters"].items():
                td = cells[name]
                assert float(td.get_attribute("data-value")) == score["pi"], (name, td.text)
            best = min(run["filters"], key=lambda n: run["filters"][n]["pi"])
            assert "best" in cells[best].get_attribute("class"), best
        run_name = rows[0].get_attribute("data-key")  # the run the page shows first
        # Sorting by a column orders the rows by it.
        driver.find_element(By.CSS_SELECTOR, '#pi-table th[data-col="median"]').click()
        values = [float(td.get_attribute("data-value")) for td in driver.find_elements(
            By.CSS_SELECTOR, '#pi-table tbody td[data-col="median"]')]
        assert values == sorted(values), values
        # The value under the pointer is the TIFF's value at that cell, in every panel.
        maps_dir = os.path.join(folder, "runs", run_name)
        with open(os.path.join(maps_dir, "maps.json")) as f:
            layers = json.load(f)["layers"]
        WebDriverWait(driver, 30).until(
            lambda d: d.find_elements(By.CSS_SELECTOR, 'canvas[data-layer="raw"]'))
        tiffs = {l["name"]: cv2.imread(os.path.join(maps_dir, l["file"]), cv2.IMREAD_UNCHANGED)
                 for l in layers}
        vis_rows, vis_cols = visible_cells(driver, "raw")
        row, col = pick_cell([tiffs["raw"]], vis_rows, vis_cols)
        point_at_cell(driver, "raw", row, col)
        assert int(info_value(driver, '[data-field="row"]')) == row
        assert int(info_value(driver, '[data-field="col"]')) == col
        for name, tiff in tiffs.items():
            shown = info_value(driver, '[data-layer="%s"]' % name)
            assert same_float(shown, tiff[row, col]), (name, shown, tiff[row, col])
        print("bench: %d PI rows equal bench.json; cell (%d, %d) equals the TIFFs in %d panels "
              "(raw %.4f m)" % (len(rows), row, col, len(tiffs), tiffs["raw"][row, col]))
        driver.save_screenshot(os.path.join(out, "bench.png"))
    finally:
        view.close()


def test_sweep(driver, casmap, folder, out):
    with open(os.path.join(folder, "sweep.json")) as f:
        sweep = json.load(f)
    view = View(casmap, folder)
    try:
        open_page(driver, view.url)
        rows = driver.find_elements(By.CSS_SELECTOR, "#points-table tbody tr")
        assert len(rows) == len(sweep["points"])
        if len(sweep["parameters"]) == 2:
            canvas = driver.find_element(By.ID, "heat-canvas")
            driver.execute_script("arguments[0].scrollIntoView({block: 'center'});", canvas)
            rect = driver.execute_script("return arguments[0].getBoundingClientRect().toJSON();",
                                         canvas)
            # The first heat cell (lowest x value, highest y value) is at the top left.
            actions = ActionBuilder(driver)
            actions.pointer_action.move_to_location(int(rect["left"] + 80), int(rect["top"] + 16))
            actions.pointer_action.click()
            actions.perform()
            px, py = sweep["parameters"]
            xs = sorted({p["params"][px] for p in sweep["points"]})
            ys = sorted({p["params"][py] for p in sweep["points"]})
            shown = {td.get_attribute("data-param"): float(td.text) for td in
                     driver.find_elements(By.CSS_SELECTOR, "#point-details td[data-param]")}
            assert math.isclose(shown[px], xs[0], rel_tol=1e-3), shown
            assert math.isclose(shown[py], ys[-1], rel_tol=1e-3), shown
        print("sweep: %d points listed; heat map click shows the point's parameters"
              % len(rows))
        driver.save_screenshot(os.path.join(out, "sweep.png"))
    finally:
        view.close()


def test_dataset(driver, casmap, folder, out):
    with open(os.path.join(folder, "manifest.jsonl")) as f:
        lines = [json.loads(l) for l in f if l.strip()]
    view = View(casmap, folder)
    try:
        open_page(driver, view.url)
        rows = driver.find_elements(By.CSS_SELECTOR, "#manifest-table tbody tr")
        assert len(rows) == len(lines), (len(rows), len(lines))
        split = lines[0].get("split")
        if split:
            box = driver.find_element(By.ID, "manifest-filter")
            box.send_keys("split=" + split)
            kept = driver.find_elements(By.CSS_SELECTOR, "#manifest-table tbody tr")
            assert len(kept) == sum(1 for l in lines if l.get("split") == split)
            box.clear()
            box.send_keys(" ")
        driver.find_elements(By.CSS_SELECTOR, "#manifest-table tbody tr")[0].click()
        WebDriverWait(driver, 30).until(
            lambda d: d.find_elements(By.CSS_SELECTOR, 'canvas[data-layer="elevation_m"]'))
        run = lines[0]["dir"] + "/" + [f["path"] for f in lines[0]["files"]
                                       if f["path"].endswith(".h5")][0]
        with h5py.File(os.path.join(folder, run), "r") as h5:
            raw = h5["maps/elevation_m"][()]
        vis_rows, vis_cols = visible_cells(driver, "elevation_m")
        row, col = pick_cell([raw], vis_rows, vis_cols)
        point_at_cell(driver, "elevation_m", row, col)
        shown = info_value(driver, '[data-layer="elevation_m"]')
        assert same_float(shown, raw[row, col]), (shown, raw[row, col])
        print("dataset: %d manifest rows; sample cell (%d, %d) equals the run file (%.4f m)"
              % (len(rows), row, col, raw[row, col]))
        driver.save_screenshot(os.path.join(out, "dataset.png"))
    finally:
        view.close()


def test_live(driver, casmap, folder, out, url=None):
    view = None if url else View(casmap, folder)
    try:
        open_page(driver, url or view.url)

        def scans():
            els = driver.find_elements(By.CSS_SELECTOR, "#live-scans .v")
            return float(els[0].get_attribute("data-value")) if els else None

        WebDriverWait(driver, 30).until(lambda d: scans() is not None)
        first = scans()
        WebDriverWait(driver, 30, poll_frequency=0.2).until(lambda d: scans() > first)
        WebDriverWait(driver, 30).until(lambda d: d.find_elements(By.CSS_SELECTOR,
                                                                  "#live-map-body canvas"))
        print("live: scan count rose from %d to %d on the page" % (first, scans()))
        driver.save_screenshot(os.path.join(out, "live.png"))
    finally:
        if view:
            view.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--casmap", required=True)
    parser.add_argument("--out", required=True)
    for name in ("bench", "sweep", "dataset", "live"):
        parser.add_argument("--" + name)
    parser.add_argument("--live-url", help="a page already served (casmap live --view)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    failed = 0
    with tempfile.TemporaryDirectory(prefix="casmap-view-chromium-") as profile:
        driver = make_driver(profile)
        try:
            for name, test in (("bench", test_bench), ("sweep", test_sweep),
                               ("dataset", test_dataset), ("live", test_live)):
                folder = getattr(args, name)
                if not folder:
                    continue
                try:
                    if name == "live" and args.live_url:
                        test(driver, args.casmap, folder, args.out, args.live_url)
                    else:
                        test(driver, args.casmap, folder, args.out)
                except Exception as e:  # report every test, fail at the end
                    failed += 1
                    driver.save_screenshot(os.path.join(args.out, name + "-failed.png"))
                    print("FAILED %s: %s: %s" % (name, type(e).__name__, e), file=sys.stderr)
        finally:
            driver.quit()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
