#!/bin/sh
# casmap bench under mpirun: 2 MPI ranks give the same outputs as one process (bench.json
# compared without its elapsed_s and threads; every other file byte for byte).
# Usage: bench_mpi_test.sh CASMAP MPIRUN SOURCE_DIR
set -eu
casmap=$1
mpirun=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$src"
# Every named pipeline and a terrain scene run too (the wire carries all their scores).
more="--pipelines all --scenes scenes/outdoor.yaml"
"$casmap" bench --courses 4 --tests T,TR $more --out "$work/one" --threads 1 > /dev/null
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader \
    "$mpirun" --oversubscribe -n 2 "$casmap" bench --courses 4 --tests T,TR $more --out "$work/two" \
    --threads 1 > "$work/two.txt"
grep -q "2 rank(s)" "$work/two.txt"
diff -r -x bench.json "$work/one" "$work/two"
/usr/bin/python3 - "$work/one/bench.json" "$work/two/bench.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("elapsed_s", None)
    d.pop("threads", None)
assert a == b, "bench.json differs between 1 process and 2 ranks"
PY
echo "bench: 1 process and 2 ranks agree"
