#!/usr/bin/env bash
# Builds the tinybvh side-by-side harness against a tinybvh checkout you fetched
# yourself (nothing of tinybvh is kept in this repository):
#   git clone https://github.com/jbikker/tinybvh && TINYBVH_DIR=$PWD/tinybvh
#   TINYBVH_DIR=... benchmarks/rays/tinybvh/build.sh [OUTPUT_BINARY]
# Needs g++ and the OpenCL headers and ICD loader (Debian: opencl-headers, ocl-icd-opencl-dev).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
: "${TINYBVH_DIR:?set TINYBVH_DIR to a tinybvh checkout (the folder holding tiny_bvh.h and traverse.cl)}"
for f in tiny_bvh.h traverse.cl traverse_bvh2.cl traverse_bvh4.cl traverse_cwbvh.cl; do
  [ -f "$TINYBVH_DIR/$f" ] || { echo "build.sh: error: $TINYBVH_DIR/$f: no such file" >&2; exit 1; }
done
OUT=${1:-$ROOT/build/tinybvh-rays/tinybvh_rays}
mkdir -p "$(dirname "$OUT")"
# -fno-strict-aliasing: tiny_bvh.h type-puns through pointer casts (BVH4_GPU::ConvertFrom,
# as_uint); g++ -O2 without it builds BVH4_GPU data in which no ray finds a hit.
g++ -std=c++17 -O2 -fno-strict-aliasing -march=native -pthread -Wall -Wextra -isystem "$TINYBVH_DIR" \
  "$HERE/tinybvh_rays.cpp" -o "$OUT" -lOpenCL
echo "build.sh: built $OUT (tinybvh $(git -C "$TINYBVH_DIR" rev-parse --short HEAD 2>/dev/null || echo 'of unknown commit') from $TINYBVH_DIR)"
