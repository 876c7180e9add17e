#!/usr/bin/env bash
# Installs the dependencies, builds casmap and runs the main job: the paper's benchmark on
# obstacle course 4, test T (the course of the paper's Fig. 6 and 7). Prints the PI table and
# writes the maps and charts to out/bench (casmap view out/bench shows them in a browser). Idempotent; as root or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache (used when installed) keys on paths relative to the clone, so any clone reuses it.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
./build/apps/casmap/casmap bench --courses 4 --tests T --seed 1 --maps --out out/bench "$@"
