#!/usr/bin/env bash
# Builds what benchmarks/gpu/run_gpu_checks.sh runs on a GPU machine that can
# install nothing: a build of the renderer and the cross-device test without
# OpenImageIO, the viewer, Embree or MPI (images as PFM), and the shared
# libraries it needs beyond OpenCL and the C++ runtime, into .gpu/ (ignored
# by git; carry it). Usage, from the repository root: benchmarks/gpu/build_gpu_bundle.sh
set -eu
cmake -B build-gpu -DCMAKE_BUILD_TYPE=Release -DCLPATH_WITH_OIIO=OFF -DCLPATH_WITH_VIEWER=OFF \
  -DCLPATH_WITH_EMBREE=OFF -DCLPATH_WITH_MPI=OFF >/dev/null
cmake --build build-gpu -j"$(nproc)" --target clpath reference_agreement_test
rm -rf .gpu && mkdir -p .gpu/lib .gpu/tests
cp build-gpu/clpath .gpu/
cp build-gpu/tests/reference_agreement_test .gpu/tests/
# The libraries outside the C library, the C++ runtime and OpenCL's loader.
for bin in .gpu/clpath .gpu/tests/reference_agreement_test; do
  ldd "$bin" | awk '$3 ~ /^\// {print $3}'
done | sort -u | grep -v -E '/(libc|libm|libstdc\+\+|libgcc_s|libOpenCL|ld-linux[^/]*)\.so' | xargs -r cp -L -t .gpu/lib/
# The bunny scene reads Debian's glmark2-data copy of the mesh, which the GPU
# machine lacks: the mesh travels, and the scene file is rewritten to it.
mkdir -p .gpu/scenes
cp /usr/share/glmark2/models/bunny.obj .gpu/scenes/
sed 's#/usr/share/glmark2/models/bunny.obj#bunny.obj#' scenes/bunny.json >.gpu/scenes/bunny.json
git rev-parse --short HEAD >.gpu/COMMIT
du -sh .gpu
