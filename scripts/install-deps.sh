#!/usr/bin/env bash
# Installs every Debian 12 package casmap's build, tests and benchmarks need.
# Idempotent: apt-get skips what is already installed. Runs as root or through sudo.
set -euo pipefail

packages=(
    build-essential cmake ninja-build pkg-config git
    libeigen3-dev libembree-dev libbullet-dev libassimp-dev
    libopencv-dev libyaml-cpp-dev libcli11-dev libhdf5-dev libdeflate-dev
    libgtest-dev libgmock-dev libbenchmark-dev libtiff-dev
    clang libclang-rt-14-dev clang-format xxd
    python3 python3-dev python3-numpy python3-scipy python3-h5py python3-opencv python3-pytest
    nlohmann-json3-dev pybind11-dev libopenmpi-dev openmpi-bin ccache
    libcpp-httplib-dev chromium chromium-driver python3-selenium
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

if [ "${#missing[@]}" -gt 0 ]; then
    echo "install-deps: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update -q
    "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
else
    echo "install-deps: all ${#packages[@]} packages present"
fi
