#!/bin/sh
# casmap sweep under mpirun: 2 MPI ranks give the same outputs as one process (sweep.json
# compared without its elapsed_s and threads; every other file byte for byte), with training
# seeds, a held-out seed and a growth round, so the broadcast between rounds is exercised.
# Usage: sweep_mpi_test.sh CASMAP MPIRUN SOURCE_DIR
set -eu
casmap=$1
mpirun=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$src"
args="--set A=12:24:12 --set h_sum_min=7:9:2 --courses 4 --tests T,TR --train-seeds 1 --test-seeds 2 --grow 1 --threads 1"
"$casmap" sweep $args --out "$work/one" > /dev/null
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader \
    "$mpirun" --oversubscribe -n 2 "$casmap" sweep $args --out "$work/two" > "$work/two.txt"
grep -q "2 rank(s)" "$work/two.txt"
diff -r -x sweep.json "$work/one" "$work/two"
/usr/bin/python3 - "$work/one/sweep.json" "$work/two/sweep.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("elapsed_s", None)
    d.pop("threads", None)
assert a == b, "sweep.json differs between 1 process and 2 ranks"
assert a["held_out"]["runs"], "no held-out runs"
PY
# Coordinate descent decides its next line from the scores: the same path on 2 ranks.
"$casmap" sweep $args --search descent --out "$work/d1" > /dev/null
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader \
    "$mpirun" --oversubscribe -n 2 "$casmap" sweep $args --search descent --out "$work/d2" \
    > /dev/null
/usr/bin/python3 - "$work/d1/sweep.json" "$work/d2/sweep.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("elapsed_s", None)
    d.pop("threads", None)
assert a == b, "descent sweep.json differs between 1 process and 2 ranks"
assert a["path"], "no descent path"
PY
echo "sweep: 1 process and 2 ranks agree"
