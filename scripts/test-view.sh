#!/usr/bin/env bash
# Browser tests of `casmap view` (tests/view/browser_test.py) in headless Chromium on a small
# benchmark, a small sweep, a small dataset and a `casmap live --view` run.
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

/usr/bin/python3 tests/view/browser_test.py --casmap "$casmap" --out "$out" \
    --bench "$out/bench" --sweep "$out/sweep" --dataset "$out/dataset"

# Live: casmap live --view on course 4 at the scanner's real rate (slow table: ~20 s of scans),
# its own server showing the page while it maps.
"$casmap" live --scene scenes/courses/course04.yaml --motion T --speed 0.3 --realtime \
    --out "$out/live" --snapshot-every-s 0.5 --duration 40 --view --port 0 \
    >"$out/live.json" 2>"$out/live.log" &
live=$!
trap 'kill $live 2>/dev/null || true' EXIT
url=
for _ in $(seq 200); do
    url=$(sed -n 's/^casmap live: view at \(http[^ ]*\).*/\1/p' "$out/live.log")
    [ -n "$url" ] && [ -f "$out/live/status.json" ] && break
    sleep 0.1
done
/usr/bin/python3 tests/view/browser_test.py --casmap "$casmap" --out "$out" --live "$out/live" \
    --live-url "$url"
kill $live 2>/dev/null || true
wait $live 2>/dev/null || true
echo "test-view: passed in $(($(date +%s) - start)) s; screenshots in $out"
