#!/usr/bin/env bash
# Builds the libFuzzer target for the LMS 200 telegram parser with clang (separate build-fuzz
# directory, ASan + UBSan) and runs it for a bounded time (FUZZ_SECONDS, default 60), then
# prints how many inputs it executed. Exit status non-zero if the fuzzer found a crash.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${FUZZ_SECONDS:-60}
if ! command -v clang++ >/dev/null 2>&1; then
    echo "fuzz: clang++ not found; skipped"
    exit 0
fi

cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCASMAP_BUILD_SIM=OFF -DCASMAP_BUILD_TESTS=OFF -DCASMAP_BUILD_FUZZ=ON >/dev/null
cmake --build build-fuzz --target telegram_parser_fuzz -j "$(nproc)"

# Seed corpus: the real 0xB0 capture and the manual's golden telegrams.
corpus=build-fuzz/fuzz-corpus/telegram_parser
mkdir -p "$corpus"
tr -d ' \n' < tests/data/drivers/b0_real_361_mm.hex | xxd -r -p > "$corpus/seed_b0_real"
printf '\x00\x06\x02\x80\x03\x00\xa0\x00\x10\x16\x0a' > "$corpus/seed_ack_a0"
printf '\x01\x02\x00\x05\x00\x3b\xb4\x00\x64\x00\x97\x49' > "$corpus/seed_variant"

log=build-fuzz/telegram_parser_fuzz.log
status=0
./build-fuzz/drivers/fuzz/telegram_parser_fuzz -max_total_time="$seconds" -print_final_stats=1 \
    -artifact_prefix=build-fuzz/ "$corpus" >"$log" 2>&1 || status=$?
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
if [ "$status" -ne 0 ]; then
    tail -n 40 "$log"
    echo "fuzz: telegram_parser_fuzz FAILED after ${runs:-?} executions (see $log)"
    exit "$status"
fi
echo "fuzz: telegram_parser_fuzz ran ${runs:-?} executions in ${seconds} s without a crash"
