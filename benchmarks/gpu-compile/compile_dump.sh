#!/usr/bin/env bash
# Compiles a `clpath kernels --dump DIR` folder with the stock tools, by hand,
# without clpath: each NAME.cl with the options in NAME.options, for NVIDIA
# sm_90 (clang-14 + libclc + opt/llc 14 + ptxas -v) and AMD gfx90a (the same
# with llc's kernel descriptors), printing ptxas's and the descriptors' figures.
# What `clpath kernels --report` tabulates comes out of these same steps.
# Usage: benchmarks/gpu-compile/compile_dump.sh DIR [NAME...]
set -eu
DIR=$1
shift
LIBCLC=${CLPATH_LIBCLC_DIR:-/usr/lib/clc}
PTXAS=${CLPATH_PTXAS:-/usr/local/cuda/bin/ptxas}
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in "$DIR"/*.cl; do names+=("$(basename "$f" .cl)"); done
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in "${names[@]}"; do
  # shellcheck disable=SC2046
  opts=$(cat "$DIR/$n.options")
  echo "== $n ($opts)"
  # shellcheck disable=SC2086
  clang-14 -x cl -Xclang -finclude-default-header -target nvptx64-nvidia-nvcl -O3 -emit-llvm -c $opts \
      "$DIR/$n.cl" -o "$work/nv.bc"
  llvm-link-14 "$work/nv.bc" "$LIBCLC/nvptx64--nvidiacl.bc" -o "$work/nv-linked.bc" 2> /dev/null
  opt-14 -O3 "$work/nv-linked.bc" -o "$work/nv-opt.bc"
  llc-14 -mcpu=sm_80 -mattr=+ptx75 "$work/nv-opt.bc" -o "$work/nv.ptx"
  "$PTXAS" -arch=sm_90 -v "$work/nv.ptx" -o "$work/nv.cubin" 2>&1 |
      grep -E "Compiling entry|bytes stack frame|Used [0-9]+ registers" | sed 's/^/  sm_90: /'
  # shellcheck disable=SC2086
  clang-14 -x cl -Xclang -finclude-default-header -target amdgcn-amd-amdhsa -mcpu=gfx90a -nogpulib -O3 \
      -emit-llvm -c $opts "$DIR/$n.cl" -o "$work/amd.bc"
  llvm-link-14 "$work/amd.bc" "$LIBCLC/amdgcn--amdhsa.bc" -o "$work/amd-linked.bc" 2> /dev/null
  opt-14 -O3 "$work/amd-linked.bc" -o "$work/amd-opt.bc"
  llc-14 -mtriple=amdgcn-amd-amdhsa -mcpu=gfx90a "$work/amd-opt.bc" -o "$work/amd.s"
  grep -E "^    \.(name|vgpr_count|sgpr_count|private_segment_fixed_size|vgpr_spill_count):" "$work/amd.s" |
      sed 's/^ */  gfx90a: /'
done
