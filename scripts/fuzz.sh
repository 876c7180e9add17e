#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (separate build-fuzz directory, ASan + UBSan, libraries
# instrumented for coverage) and runs each from its seed corpus, then prints how many inputs each
# executed. Exit status non-zero if any target found a crash, a sanitizer report, a leak, an
# uncaught exception or a runaway allocation (> 2 GB).
# By default (CI) each target replays its seeds and regression inputs, then makes a fixed number
# of mutations from a fixed seed: nearly the same inputs on every machine, so CI passes or fails
# for a reason anyone can reproduce (about 3 minutes in all). Exploring for new findings is a
# separate, time-bounded run with a fresh seed:
#   FUZZ_SECONDS   explore: seconds per target, random seed (unset: the fixed CI run)
#   FUZZ_SEED      the CI run's seed (default 1)
#   FUZZ_TARGETS   space-separated subset (default: all)
# Long runs: docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${FUZZ_SECONDS:-}
seed=${FUZZ_SEED:-1}
# The CI run's mutations per target: about 20 s each at the rates of docs/fuzzing.md.
runs_for() {
    case $1 in
        telegram_parser) echo 200000 ;;
        run_file) echo 3000 ;;
        mesh) echo 2500 ;;
        scene_yaml | rig_yaml) echo 25000 ;;
        sensor_yaml) echo 30000 ;;
        deflate) echo 8000 ;;
        *) echo 60000 ;;
    esac
}
all="telegram_parser_fuzz pose_file_fuzz run_file_fuzz tiff_map_fuzz scene_yaml_fuzz \
sensor_yaml_fuzz rig_yaml_fuzz mesh_fuzz deflate_fuzz"
targets=${FUZZ_TARGETS:-$all}
if ! command -v clang++ >/dev/null 2>&1; then
    echo "fuzz: clang++ not found; skipped"
    exit 0
fi

cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCASMAP_BUILD_SIM=ON -DCASMAP_BUILD_TESTS=OFF -DCASMAP_BUILD_FUZZ=ON >/dev/null
# shellcheck disable=SC2086
cmake --build build-fuzz --target $targets -j "$(nproc)"

# Seed corpora: tests/data/fuzz/<target without _fuzz>/, copied so the repository stays clean.
seeds() {
    local name=$1 corpus=$2
    rm -rf "$corpus"
    mkdir -p "$corpus"
    if [ "$name" = telegram_parser ]; then
        # The real 0xB0 capture and the manual's golden telegrams.
        tr -d ' \n' < tests/data/drivers/b0_real_361_mm.hex | xxd -r -p > "$corpus/seed_b0_real"
        printf '\x00\x06\x02\x80\x03\x00\xa0\x00\x10\x16\x0a' > "$corpus/seed_ack_a0"
        printf '\x01\x02\x00\x05\x00\x3b\xb4\x00\x64\x00\x97\x49' > "$corpus/seed_variant"
    else
        cp tests/data/fuzz/"$name"/* "$corpus"/
    fi
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
failed=0
for target in $targets; do
    name=${target%_fuzz}
    corpus=build-fuzz/fuzz-corpus/$name
    seeds "$name" "$corpus"
    binary=$(find build-fuzz -type f -name "$target" -perm -u+x | head -n 1)
    log=build-fuzz/$target.log
    status=0
    # The telegram target's inputs are a byte stream: 1024 bytes hold the longest frame (814)
    # and what surrounds it; longer inputs only make the parser's resync replay slower.
    max_len=()
    [ "$name" = telegram_parser ] && max_len=(-max_len=1024)
    # HDF5 asks malloc for impossible sizes on corrupt files and handles a null answer (a
    # normal build gets an error); ASan would abort on the request itself.
    asan=$ASAN_OPTIONS
    [ "$name" = run_file ] && asan=$ASAN_OPTIONS:allocator_may_return_null=1
    if [ -n "$seconds" ]; then
        budget=(-max_total_time="$seconds")
    else
        budget=(-seed="$seed" -runs="$(runs_for "$name")")
    fi
    ASAN_OPTIONS=$asan "$binary" "${max_len[@]}" "${budget[@]}" -rss_limit_mb=2048 -timeout=10 -timeout_exitcode=77 \
        -print_final_stats=1 -artifact_prefix="build-fuzz/$target-" "$corpus" >"$log" 2>&1 ||
        status=$?
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    if [ "$status" -ne 0 ]; then
        tail -n 40 "$log"
        echo "fuzz: $target FAILED after ${runs:-?} executions (see $log)"
        failed=1
    else
        echo "fuzz: $target ran ${runs:-?} executions (${budget[*]}) without a finding"
    fi
done
exit "$failed"
