#!/bin/sh
# scripts/scoreboard.py over a small `casmap bench --pipelines all` (courses 4 and 5, T and TP):
# every pipeline gets a row in every test table with its figures from bench.json, the win counts
# add up, the "## Scoreboard" section of a results page is replaced and the rest kept, and bad
# input exits 2 naming the file.
# Usage: scoreboard_test.sh CASMAP SOURCE_DIR
set -eu
casmap=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$casmap" bench --courses 4,5 --tests T,TP --pipelines all --seed 1 --no-sheets --threads 2 \
    --courses-dir "$src/scenes/courses" --out "$work/b" > /dev/null
printf '# Results\n\nintro\n\n## Scoreboard: old\n\nold table\n\n### old sub\n\n## Tuning\n\nkept\n' \
    > "$work/results.md"
/usr/bin/python3 "$src/scripts/scoreboard.py" --courses "$work/b/bench.json" \
    --terrain "again=$work/b/bench.json" --command "test" --seed 1 --preset paper \
    --commit abc1234 --date "today" --results "$work/results.md"
/usr/bin/python3 - "$work/b/bench.json" "$work/results.md" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
text = open(sys.argv[2]).read()
assert text.startswith("# Results\n\nintro\n\n## Scoreboard: every named pipeline"), text[:200]
assert "old table" not in text and "### old sub" not in text, text
assert text.rstrip().endswith("## Tuning\n\nkept"), text[-200:]
assert "`test` at commit abc1234, today; simulator seed 1, preset `paper`" in text
names = list(runs[0]["filters"])
assert len(names) >= 17, names
for test in ["T", "TP"]:
    part = text.split(f"#### Test {test} (2 courses)")[1].split("\n###")[0]
    rows = [l for l in part.splitlines() if l.startswith("| ") and not l.startswith("| pipeline")]
    assert [r.split(" | ")[0][2:] for r in rows] == names, rows
    rs = [r for r in runs if r["test"] == test]
    wins = 0
    for r in rows:
        cells = [c.strip() for c in r.strip("|").split("|")]
        name = cells[0]
        pi = sum(x["filters"][name]["pi"] for x in rs) / len(rs)
        assert cells[1] == f"{pi:.3f}", (name, cells[1], pi)
        rmse = sum(x["filters"][name]["rmse_m"] for x in rs) / len(rs) * 1000
        assert cells[5] == f"{rmse:.1f}", (name, cells[5], rmse)
        kept = sum(len(x["poles_kept"][name]) for x in rs)
        poles = sum(len(x["poles"]) for x in rs)
        assert cells[7] == f"{kept}/{poles}", (name, cells[7])
        wins += int(cells[2].split("/")[0])
    assert wins >= len(rs), wins  # every run has at least one lowest-PI pipeline
assert "### Lowest-PI wins per test" in text and "### Terrain runs" in text
print("scoreboard ok:", len(names), "pipelines")
PY
# Two seeds: wins per test and seed, detailed tables pooled over the seeds.
"$casmap" bench --courses 4,5 --tests T,TP --pipelines all --seed 2 --no-sheets --threads 2 \
    --courses-dir "$src/scenes/courses" --out "$work/b2" > /dev/null
/usr/bin/python3 "$src/scripts/scoreboard.py" --courses "$work/b/bench.json" \
    --courses "$work/b2/bench.json" --command "test" --seed 1,2 --preset paper > "$work/two.md"
grep -q '^| pipeline | T s1 | T s2 | TP s1 | TP s2 | every pole kept | RMSE below Kalman |$' \
    "$work/two.md"
grep -q '^#### Test TP (4 runs: 2 courses x seeds 1, 2)$' "$work/two.md"
grep -q '^| cas | [0-9.]* | [0-9]/4 |' "$work/two.md"
# Bad input: exit 2, the file named.
if /usr/bin/python3 "$src/scripts/scoreboard.py" --courses "$work/none.json" --command x \
    --seed 1 --preset paper 2> "$work/err"; then
    echo "accepted a missing bench.json"; exit 1
fi
grep -q "none.json" "$work/err"
