#!/usr/bin/env bash
# Dataset throughput on this machine, measured in one run: samples/s of `casmap dataset` with
# 1 process (1 thread) and with 2 MPI ranks on the same spec and count, the parallel efficiency
# (2-rank rate / (2 x 1-rank rate)), the mean sample size and the time and size a 1000-sample
# dataset would take at the 2-rank rate (extrapolated).
# Usage: scripts/dataset-speed.sh [COUNT=40] [SPEC=config/datasets/default.yaml] [CASMAP]
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-40}
spec=${2:-config/datasets/default.yaml}
casmap=${3:-build/apps/casmap/casmap}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader

# "wall_s cpu_s" of a command (cpu = user + system of it and its children, mpirun's ranks too).
timed() {
    local t0 t1 c
    t0=$(date +%s.%N)
    c=$( { TIMEFORMAT='%U %S'; time "$@" > /dev/null; } 2>&1 | tail -1)
    t1=$(date +%s.%N)
    echo "$(echo "$t1 - $t0" | bc -l) $(echo "$c" | awk '{print $1 + $2}')"
}

load=$(cut -d' ' -f1 /proc/loadavg)
read -r t1 c1 < <(timed "$casmap" dataset --spec "$spec" --out "$work/one" --count "$count" --threads 1)
read -r t2 c2 < <(timed mpirun --oversubscribe -n 2 "$casmap" dataset --spec "$spec" \
    --out "$work/two" --count "$count" --threads 1)
diff -r -q "$work/one" "$work/two" > /dev/null && same=yes || same=NO
bytes=$(du -sb "$work/two/samples" | cut -f1)
ok=$(grep -c '"status":"ok"' "$work/two/manifest.jsonl" || true)
largest=$(find "$work/two/samples" -mindepth 1 -maxdepth 1 -type d -exec du -sb {} + | sort -n | tail -1 | cut -f1)
awk -v n="$count" -v t1="$t1" -v t2="$t2" -v c1="$c1" -v c2="$c2" -v load="$load" -v cores="$(nproc)" -v b="$bytes" -v ok="$ok" -v big="$largest" -v same="$same" 'BEGIN {
    r1 = n / t1; r2 = n / t2;
    printf "samples: %d (%d ok); load average before: %s on %d cores\n", n, ok, load, cores;
    printf "1 process, 1 thread: %.1f s wall, %.1f s CPU, %.3f samples/s\n", t1, c1, r1;
    printf "mpirun -n 2:         %.1f s wall, %.1f s CPU, %.3f samples/s\n", t2, c2, r2;
    printf "parallel efficiency (wall): %.2f (2-rank rate / (2 x 1-rank rate); meaningful only on idle cores)\n", r2 / (2 * r1);
    printf "CPU efficiency: %.2f (1-rank CPU / 2-rank CPU for the same samples)\n", c1 / c2;
    printf "CPU per sample: %.3f s -> %.2f samples/s per idle core\n", c1 / n, n / c1;
    printf "byte-identical 1 vs 2 ranks: %s\n", same;
    printf "mean sample: %.2f MB, largest %.2f MB\n", b / n / 1e6, big / 1e6;
    printf "1000 samples at the 2-rank rate (extrapolated): %.0f s (%.1f min), %.2f GB\n",
        1000 / r2, 1000 / r2 / 60, 1000 * b / n / 1e9;
    printf "1000 samples on 2 idle cores (2-rank CPU per sample / 2, extrapolated): %.0f s (%.1f min)\n",
        1000 * c2 / n / 2, 1000 * c2 / n / 2 / 60;
}'
