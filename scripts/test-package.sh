#!/usr/bin/env bash
# The installed package, as a user sees it: installs the build in BUILD (default build/) to a
# temporary prefix, builds examples/ standalone against it with find_package(casmap), runs each
# example on short inputs (simulate_and_map must print the PI line of `casmap bench`), and runs
# the pytest suite against the installed Python module. With a robot build (no simulator) the
# simulator examples and tests are left out. A few minutes on two cores.
#   scripts/test-package.sh [BUILD [ROBOT_BUILD]]     (default: build build-nosim, if present)
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
python=/usr/bin/python3
jobs=$(nproc)
work=$(mktemp -d)
serve_pid=
cleanup() {
    [[ -n "$serve_pid" ]] && kill "$serve_pid" 2>/dev/null || true
    rm -rf "$work"
}
trap cleanup EXIT
prefix=$work/prefix


# check_view_consumer PREFIX: a project of its own that links casmap::view and runs.
check_view_consumer() {
    local dir=$work/view-consumer
    mkdir -p "$dir"
    cat >"$dir/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.20)
project(view_consumer CXX)
find_package(casmap REQUIRED)
add_executable(view_consumer main.cpp)
target_link_libraries(view_consumer PRIVATE casmap::view)
CMAKE
    cat >"$dir/main.cpp" <<'CPP'
#include <cstdio>

#include "casmap/view/server.hpp"

int main() {
    const bool ok = casmap::view::IsLoopback("127.0.0.1") && !casmap::view::IsLoopback("0.0.0.0");
    std::puts(ok ? "view consumer: ok" : "view consumer: wrong answer");
    return ok ? 0 : 1;
}
CPP
    cmake -S "$dir" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$1" >/dev/null
    cmake --build "$dir/build" >/dev/null
    "$dir/build/view_consumer"
}

# check_install BUILD: install BUILD, build the examples standalone against it, run them.
check_install() {
    local build=$1 prefix=$work/prefix-$(basename "$1")
    local ex=$work/examples-$(basename "$1")
    echo "== test-package: $build -> $prefix"
    cmake --install "$build" --prefix "$prefix" >/dev/null
    for private in io/hdf5_util.hpp io/yaml_util.hpp drivers/telegram_detail.hpp \
                   drivers/virtual_lms200_impl.hpp sensor_models/scratch_array.hpp; do
        if [[ -e "$prefix/include/casmap/$private" ]]; then
            echo "test-package: private header $private was installed" >&2
            return 1
        fi
    done
    local with_sim=0
    grep -q 'set(casmap_WITH_SIM ON)' "$prefix/lib/cmake/casmap/casmapConfig.cmake" && with_sim=1

    # The examples as a user's project: only the installed prefix on the search path.
    cmake -S examples -B "$ex" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
    cmake --build "$ex" -j "$jobs" >/dev/null
    # casmap::view (static, private deps cpp-httplib and nlohmann_json) links in a consumer.
    if grep -q 'set(casmap_WITH_VIEW ON)' "$prefix/lib/cmake/casmap/casmapConfig.cmake"; then
        check_view_consumer "$prefix"
    fi
    local casmap=$prefix/bin/casmap
    export CASMAP_DATA_DIR=$prefix/share/casmap
    export PYTHONPATH=$prefix/$($python -c "import sysconfig; print(sysconfig.get_path('platlib', 'posix_prefix', vars={'platbase': '.', 'base': '.'}))")

    # filter_tiff (C++ and Python) on the synthetic map pair of `casmap demo`.
    "$casmap" demo --out "$work/demo" >/dev/null
    "$ex/filter_tiff" "$work/demo/elevation.tiff" "$work/demo/certainty.tiff" k=2
    $python examples/python/filter_tiff.py "$work/demo/elevation.tiff" \
        "$work/demo/certainty.tiff" k=2

    if ((with_sim)); then
        # A short run for read_run and the live example.
        "$casmap" simulate --scene "$CASMAP_DATA_DIR/scenes/courses/course04.yaml" --motion T \
            --seed 1 --out "$work/run.h5" >/dev/null
        # simulate_and_map prints the PI line of `casmap bench` (C++ and Python).
        "$casmap" bench --courses 4 --tests T --seed 1 --no-sheets --out "$work/bench" \
            | grep '^ *4 T ' >"$work/bench_line.txt"
        "$ex/simulate_and_map" | grep '^ *4 T ' >"$work/cpp_line.txt"
        $python examples/python/simulate_and_map.py "$CASMAP_DATA_DIR" >"$work/py_line.txt"
        cat "$work/bench_line.txt"
        diff "$work/bench_line.txt" "$work/cpp_line.txt"
        diff "$work/bench_line.txt" "$work/py_line.txt"
    fi
    "$ex/read_run" "$work/run.h5"
    $python examples/python/read_run.py "$work/run.h5"
    $python examples/python/read_run_h5py.py "$work/run.h5"
    $python examples/python/stream_map.py "$work/run.h5"

    # live_record_and_map against the virtual scanner serving the run.
    "$casmap" serve --run "$work/run.h5" --link "$work/lms" >/dev/null 2>&1 &
    serve_pid=$!
    for _ in $(seq 50); do [[ -e "$work/lms" ]] && break; sleep 0.1; done
    "$ex/live_record_and_map" "$work/lms" 40
    kill "$serve_pid" 2>/dev/null || true
    wait "$serve_pid" 2>/dev/null || true
    serve_pid=

    # pytest against the installed module and program (exit code 5: no tests collected).
    if [[ ! -d "$PYTHONPATH/casmap" ]]; then
        echo "test-package: no Python module in $prefix (pybind11 missing?): pytest skipped"
        return 0
    fi
    local rc=0
    CASMAP_EXE=$casmap $python -m pytest -q -p no:cacheprovider python/tests || rc=$?
    if ((rc != 0 && rc != 5)); then
        return "$rc"
    fi
}

builds=("$@")
if ((${#builds[@]} == 0)); then
    builds=(build)
    [[ -d build-nosim ]] && builds+=(build-nosim)
fi
for b in "${builds[@]}"; do
    check_install "$(realpath "$b")"
done
echo "test-package: ok"
