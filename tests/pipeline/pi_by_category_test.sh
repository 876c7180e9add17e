#!/bin/sh
# scripts/pi_by_category.py over a small `casmap bench --maps` (course 4, T and TP): every
# pipeline's categories add up to its PI in bench.json (raw: 1), --diff gives A's minus B's, and
# bad input exits 2 naming the file.
# Usage: pi_by_category_test.sh CASMAP SOURCE_DIR
set -eu
casmap=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$casmap" bench --courses 4 --tests T,TP --pipelines all --seed 1 --no-sheets --maps \
    --threads 2 --courses-dir "$src/scenes/courses" --preset "$src/config/presets/cas_hybrid.yaml" \
    --out "$work/b" > /dev/null
/usr/bin/python3 "$src/scripts/pi_by_category.py" "$work/b" \
    --pipelines raw,cas_hybrid,cas_median > "$work/split.md"
/usr/bin/python3 "$src/scripts/pi_by_category.py" "$work/b" \
    --diff cas_hybrid,cas_median > "$work/diff.md"
/usr/bin/python3 - "$work/b/bench.json" "$work/split.md" "$work/diff.md" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
def rows(path):
    out = {}
    for line in open(path):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells[0] in ("T", "TP"):
            out[(cells[0], cells[1])] = [float(c) for c in cells[2:]]
    return out
split = rows(sys.argv[2])
assert len(split) == 6, split.keys()
for (test, name), cells in split.items():
    pi = [r["filters"][name]["pi"] if name != "raw" else 1.0 for r in runs if r["test"] == test][0]
    assert abs(cells[0] - pi) < 1e-4, (test, name, cells[0], pi)   # the total is the PI
    assert abs(sum(cells[1:]) - cells[0]) < 1e-3, (test, name)      # categories add up
    assert len(cells) == 1 + 18, len(cells)                         # 9 categories x known/unknown
# The pole's halo is a large share of the raw map's error; cas_hybrid removes most of it.
assert split[("T", "raw")][3] > 5 * split[("T", "cas_hybrid")][3], split
diff = rows(sys.argv[3])
for test in ("T", "TP"):
    d = diff[(test, "cas_hybrid-cas_median")]
    want = split[(test, "cas_hybrid")][0] - split[(test, "cas_median")][0]
    assert abs(d[0] - want) < 1e-3, (test, d[0], want)
print("pi_by_category ok")
PY
# Bad input: exit 2, the file named.
if /usr/bin/python3 "$src/scripts/pi_by_category.py" "$work/none" 2> "$work/err"; then
    echo "accepted a missing bench"; exit 1
fi
grep -q "none/bench.json" "$work/err"
printf 'not a tiff' > "$work/b/runs/course04_T/truth.tif"
if /usr/bin/python3 "$src/scripts/pi_by_category.py" "$work/b" 2> "$work/err"; then
    echo "accepted a bad TIFF"; exit 1
fi
grep -q "truth.tif: not a TIFF file" "$work/err"
