#!/usr/bin/env bash
# Browser tests of `casmap view` (tests/view/browser_test.py) in headless Chromium on a small
# benchmark, a small sweep, a small dataset and a live folder (until `casmap live` exists, a
# writer here rewrites status.json and a snapshot TIFF in its documented format).
# Usage: scripts/test-view.sh [BUILD_DIR]   (default: build). Screenshots: BUILD_DIR/test-view/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
casmap=$build/apps/casmap/casmap
out=$build/test-view
rm -rf "$out"
mkdir -p "$out"
start=$(date +%s)

"$casmap" bench --courses 4 --tests T --seed 1 --maps --out "$out/bench" --threads 2 >/dev/null
"$casmap" sweep --set A=12:24:12 --set h_sum_min=3:6:3 --courses 4 --tests T --seed 1 \
    --out "$out/sweep" --threads 2 >/dev/null

# Dataset: three samples of the default spec (procedural scenes, randomised rig and sensor).
"$casmap" dataset --spec config/datasets/default.yaml --out "$out/dataset" --count 3 \
    --threads 2 >/dev/null

# Live: status.json rewritten atomically every 0.2 s with a rising scan count, and a snapshot
# TIFF, as casmap live --out DIR writes them.
mkdir -p "$out/live"
cp "$out/bench/runs/course04_T/raw.tif" "$out/live/window_elevation.tif"
/usr/bin/python3 - "$out/live" <<'PY' &
import json, os, sys, time
d = sys.argv[1]
for k in range(600):
    s = {"scans": 75 * k, "scans_per_s": 75.0, "latency_p99_ms": 0.18, "dropped_scans": 0,
         "crc_errors": 0, "source": "test writer"}
    with open(os.path.join(d, ".status.tmp"), "w") as f:
        json.dump(s, f)
    os.replace(os.path.join(d, ".status.tmp"), os.path.join(d, "status.json"))
    time.sleep(0.2)
PY
writer=$!
trap 'kill $writer 2>/dev/null || true' EXIT
sleep 0.5

/usr/bin/python3 tests/view/browser_test.py --casmap "$casmap" --out "$out" \
    --bench "$out/bench" --sweep "$out/sweep" --dataset "$out/dataset" --live "$out/live"
echo "test-view: passed in $(($(date +%s) - start)) s; screenshots in $out"
