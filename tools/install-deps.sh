#!/bin/sh
# Installs everything clpath needs to build, test and benchmark, from Debian packages only.
# Run as root on Debian 12. Safe to run again: apt skips what is already there.
set -eu
export DEBIAN_FRONTEND=noninteractive
if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps.sh: run as root (it calls apt-get install)" >&2
    exit 1
fi
# libclang-rt-14-dev holds libFuzzer and the sanitizer runtimes for the fuzz tests;
# clang only recommends it, and recommends are not installed here.
# xauth: xvfb-run (the viewer tests) needs it; xvfb only recommends it.
# libembree-dev: the CPU baselines of clpath bench rays and bench path (optional at build time).
# libopenmpi-dev, openmpi-bin: rendering over MPI ranks (optional at build
# time, but the test suite checks it).
# libxxhash-dev: the checksum of checkpoint files (xxHash's XXH3).
# oclgrind: a second OpenCL implementation, a simulator that checks every kernel
# for out-of-bounds and uninitialised accesses and data races (tests/kernels/).
packages="
    build-essential cmake pkg-config clang libclang-rt-14-dev
    pocl-opencl-icd ocl-icd-opencl-dev opencl-headers clinfo oclgrind
    libglm-dev libglfw3-dev libopenimageio-dev openimageio-tools
    libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev libgtest-dev libxxhash-dev
    xvfb xauth libimgui-dev glmark2-data
    python3-numpy python3-matplotlib
    libembree-dev
    libopenmpi-dev openmpi-bin
"
missing=""
for p in $packages; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
    apt-get update -qq
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
echo "install-deps.sh: all packages present"
