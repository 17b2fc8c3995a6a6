#!/bin/sh
# Installs everything clpath needs to build, test and benchmark: Debian packages,
# and Intel Open Image Denoise from PyPI (Debian 12 does not package it).
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
# embree-tools: Embree's own example path tracer (`pathtracer`), the peer that
# benchmarks/path_embree/pathtracer.sh times clpath and its Embree baseline against.
# valgrind: benchmarks/path_embree/instructions.sh counts both path tracers'
# instructions per ray with its callgrind tool.
# libsdl2-dev, libsdl2-image-dev, libsdl2-ttf-dev: trac0r, the thesis path tracer
# that benchmarks/trac0r/run.sh builds from its own source and times clpath against.
# libopenmpi-dev, openmpi-bin: rendering over MPI ranks (optional at build
# time, but the test suite checks it).
# libxxhash-dev: the checksum of checkpoint files (xxHash's XXH3).
# oclgrind: a second OpenCL implementation, a simulator that checks every kernel
# for out-of-bounds and uninitialised accesses and data races (tests/kernels/).
# libclc-14, llvm-14 (llvm-link, opt, llc, llvm-nm), clang-15 and llvm-15: the
# portability gate (clpath kernels --report, ctest -L gpu-portability) compiles
# every kernel program for NVIDIA sm_90 and AMD gfx90a with LLVM 14 and
# libclc's built-ins, and for AMD gfx1100 with LLVM 15 (LLVM 14 has no gfx11;
# Debian's libclc-15 would replace libclc-14, so libclc 14's bitcode serves
# both). NVIDIA's ptxas comes with the CUDA toolkit, not Debian: where
# /usr/local/cuda/bin/ptxas is missing the gate skips sm_90 and says so.
# libdraco-dev, libmeshoptimizer-dev: the decoders of Draco- and
# meshopt-compressed glTF meshes (KHR_draco_mesh_compression, EXT_meshopt_compression);
# gltfpack: the tests render its default output of a bundled model against the original.
# python3-venv: the virtual environment that holds Open Image Denoise (below).
packages="
    build-essential cmake pkg-config clang libclang-rt-14-dev
    clang-14 llvm-14 libclc-14 clang-15 llvm-15
    pocl-opencl-icd ocl-icd-opencl-dev opencl-headers clinfo oclgrind
    libglm-dev libglfw3-dev libopenimageio-dev openimageio-tools
    libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev libgtest-dev libxxhash-dev
    libdraco-dev libmeshoptimizer-dev gltfpack
    xvfb xauth libimgui-dev glmark2-data
    python3-numpy python3-matplotlib python3-venv
    libembree-dev embree-tools valgrind
    libsdl2-dev libsdl2-image-dev libsdl2-ttf-dev
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

# Intel Open Image Denoise 2 for render --denoise and the viewer's denoise key:
# the pyoidn wheel ships libOpenImageDenoise.so.2 with its CPU device (and
# TBB), which clpath loads at run time from this virtual environment
# (CLPATH_OIDN_VENV in CMakeLists.txt; host/denoise/oidn_library.cpp).
# clpath builds and runs without it; --denoise then says what is missing.
oidn_venv=/opt/clpath-oidn
oidn_version=2.5.1.0
if ! "$oidn_venv/bin/python" -c "import importlib.metadata as m; assert m.version('pyoidn') == '$oidn_version'" 2>/dev/null; then
    rm -rf "$oidn_venv"
    python3 -m venv "$oidn_venv"
    # --no-deps: only the wheel's shared libraries are used, not its Python binding (nor numpy).
    "$oidn_venv/bin/pip" install --quiet --no-deps "pyoidn==$oidn_version"
fi
echo "install-deps.sh: Open Image Denoise (pyoidn $oidn_version) in $oidn_venv"
