#!/usr/bin/env bash
# Builds the tinybvh build-time harness against a tinybvh checkout you fetched
# yourself (nothing of tinybvh is kept in this repository):
#   git clone https://github.com/jbikker/tinybvh && TINYBVH_DIR=$PWD/tinybvh
#   TINYBVH_DIR=... benchmarks/bvh_build/tinybvh/build.sh [OUTPUT_BINARY]
# Compiled as tinybvh's own CMakeLists.txt compiles its programs on Linux
# (-O3 -march=native): on a CPU with AVX, BuildDefault is BuildAVX, the
# builder tinybvh's users get.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
: "${TINYBVH_DIR:?set TINYBVH_DIR to a tinybvh checkout (the folder holding tiny_bvh.h)}"
[ -f "$TINYBVH_DIR/tiny_bvh.h" ] || { echo "build.sh: error: $TINYBVH_DIR/tiny_bvh.h: no such file" >&2; exit 1; }
OUT=${1:-$ROOT/build/tinybvh-build/tinybvh_build}
mkdir -p "$(dirname "$OUT")"
g++ -std=c++20 -O3 -march=native -pthread -isystem "$TINYBVH_DIR" "$HERE/tinybvh_build.cpp" -o "$OUT"
echo "build.sh: built $OUT (tinybvh $(git -C "$TINYBVH_DIR" rev-parse --short HEAD 2>/dev/null || echo 'of unknown commit') from $TINYBVH_DIR, -O3 -march=native)"
