#!/usr/bin/env bash
# Browser tests of `casmap view` (tests/view/browser_test.py) in headless Chromium on a small
# benchmark, a small sweep, a dataset and a live run. Uses `casmap dataset` and `casmap live`
# when this build has them, else folders in their documented format made here from `casmap
# simulate` + `casmap map` (dataset) and a writer that rewrites status.json (live).
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

# Dataset: a two-sample folder in casmap dataset's format (manifest.jsonl, dataset.yaml, one
# run file with maps per sample).
if "$casmap" dataset --help >/dev/null 2>&1; then
    "$casmap" dataset --help >"$out/dataset-help.txt"
fi
mkdir -p "$out/dataset/samples/000000" "$out/dataset/samples/000001"
i=0
for motion in T TR; do
    dir=$out/dataset/samples/00000$i
    "$casmap" simulate --scene scenes/courses/course04.yaml --motion $motion --seed $((i + 1)) \
        --out "$dir/run.h5" >/dev/null
    "$casmap" map "$dir/run.h5" --out "$dir/maps" >/dev/null
    i=$((i + 1))
done
cat >"$out/dataset/manifest.jsonl" <<'JSON'
{"index": 0, "split": "train", "seed": 1, "scene": {"kind": "course", "file": "scenes/courses/course04.yaml"}, "rig": {"kind": "table", "motion": "T"}, "files": {"run": "samples/000000/run.h5"}}
{"index": 1, "split": "val", "seed": 2, "scene": {"kind": "course", "file": "scenes/courses/course04.yaml"}, "rig": {"kind": "table", "motion": "TR"}, "files": {"run": "samples/000001/run.h5"}}
JSON
printf 'samples: 2\nsplits: {train: 0.5, val: 0.5}\n' >"$out/dataset/dataset.yaml"

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
