#!/usr/bin/env bash
# The two kernel shapes side by side on one device (bench render-ab --ab-shape:
# launch pairs alternating, images compared), on the scenes the GPU check
# times, into benchmarks/results/DEVICE_DIR/kernel-shapes/render-ab.txt.
# Usage: benchmarks/kernel_shapes.sh DEVICE_DIR [BUILD_DIR] [DEVICE]
set -eu
dir=$1 B=${2:-build} dev=${3:-}
out=benchmarks/results/$dir/kernel-shapes
mkdir -p "$out"
{
  echo "# bench render-ab --ab-shape wavefront, $(date -u +%F), commit $(git rev-parse --short HEAD)"
  for s in cornell scenes/bunny.json scenes/hard/glass-in-glass.json; do
    "$B/clpath" bench render-ab "$s" --ab-shape wavefront --width 320 --height 256 --spp 16 ${dev:+--device "$dev"} 2>/dev/null
  done
} | tee "$out/render-ab.txt"
