#!/bin/sh
# scripts/bench_wins.py on two hand-made bench.json files whose win counts, pole counts and paired
# differences are worked out below; bad input exits 2 naming the file.
# Usage: bench_wins_test.sh SOURCE_DIR
set -eu
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/s1" "$work/s2"
run() {  # course test piA polesA piB piC
    printf '{"course": %s, "test": "%s", "filters": {"A": {"pi": %s, "poles_kept": %s, "poles": 3}, "B": {"pi": %s, "poles_kept": 3, "poles": 3}, "C": {"pi": %s, "poles_kept": 3, "poles": 3}}}' "$@"
}
# s1: T course 1, A lowest; T course 2, B lowest (A kept 2 of 3 poles); TP course 1, A and B tie.
# (PIs are binary fractions, so the differences below are exact.)
printf '{"runs": [%s, %s, %s]}\n' "$(run 1 T 0.25 3 0.5 0.875)" "$(run 2 T 0.75 2 0.5 0.625)" \
    "$(run 1 TP 0.25 3 0.25 0.5)" > "$work/s1/bench.json"
# s2: T course 1, A and B tie.
printf '{"runs": [%s]}\n' "$(run 1 T 0.25 3 0.25 0.5)" > "$work/s2/bench.json"
/usr/bin/python3 "$src/scripts/bench_wins.py" "$work/s1" "$work/s2" --pipeline A --versus B \
    > "$work/out.md"
# T: 1 of 2 in s1, 1 of 1 in s2 (only s2 reaches 14 of 16's share); every pole in 2 of 3 runs;
# beaten once, by B.
grep -qx '| T | 1/2 | 1/1 | 2/3 | 1/2 | 2/3 | B 1 |' "$work/out.md"
# TP: s2 has no TP run; a tie counts as a win.
grep -qx '| TP | 1/1 | - | 1/1 | 1/1 | 1/1 | - |' "$work/out.md"
# Paired A - B in T: -0.25, +0.25, 0 -> mean 0, sd 0.25, one of three below 0.
grep -qx '| T | 3 | +0.0000 | 0.2500 | +0.00 | 0.33 |' "$work/out.md"
grep -qx '| TP | 1 | +0.0000 | 0.0000 | - | 0.00 |' "$work/out.md"
if grep -q '^| TR |' "$work/out.md"; then
    echo "printed a test without runs"; exit 1
fi
# --among C: B is no rival. T: A wins course 1 (0.25 < 0.875), C course 2 (0.625 < 0.75);
# TP: A below C.
/usr/bin/python3 "$src/scripts/bench_wins.py" "$work/s1" --pipeline A --among C > "$work/among.md"
grep -q 'against C;' "$work/among.md"
grep -qx '| T | 1/2 | 1/2 | 0/1 | 1/2 | C 1 |' "$work/among.md"
grep -qx '| TP | 1/1 | 1/1 | 1/1 | 1/1 | - |' "$work/among.md"
if /usr/bin/python3 "$src/scripts/bench_wins.py" "$work/s1" --pipeline A --among D 2> "$work/err"; then
    echo "accepted a rival the bench did not score"; exit 1
fi
grep -q "s1/bench.json: pipeline 'D' not scored" "$work/err"
# Bad input: exit 2, the file named.
if /usr/bin/python3 "$src/scripts/bench_wins.py" "$work/none" --pipeline A 2> "$work/err"; then
    echo "accepted a missing bench"; exit 1
fi
grep -q "none/bench.json" "$work/err"
if /usr/bin/python3 "$src/scripts/bench_wins.py" "$work/s1" --pipeline D 2> "$work/err"; then
    echo "accepted a pipeline the bench did not score"; exit 1
fi
grep -q "s1/bench.json: pipeline 'D' not scored" "$work/err"
echo "bench_wins ok"
