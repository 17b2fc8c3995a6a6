#!/usr/bin/env bash
# Instancing against flattening and against Embree (clpath bench instances):
# bunnies:1, :100 and :10000 (7e8 triangles placed; flattened only where it
# fits, up to 5e7), each traced by clpath's two-level walk, clpath's
# one-level BVH over the flattened scene and Embree over the instances and
# flattened (default mode and robust), ROUNDS rounds (default 3) in turn, on
# an idle machine. Writes every round's CSV and a table of the medians to
# benchmarks/results/DEVICE_DIR/instancing/.
# Usage: benchmarks/instancing/run.sh DEVICE_DIR [BUILD_DIR] [DEVICE]
set -eu
dir=$1 B=${2:-build} dev=${3:-}
rounds=${ROUNDS:-3}
out=benchmarks/results/$dir/instancing
mkdir -p "$out"
rm -f "$out"/bunnies-*.csv
for r in $(seq 1 "$rounds"); do
  for n in 1 100 10000; do
    "$B/clpath" bench instances "bunnies:$n" --width 240 --height 160 --launches 3 ${dev:+--device "$dev"} \
      --csv "$out/bunnies-$n-round$r.csv" > "$out/bunnies-$n-round$r.txt" 2>/dev/null
  done
done
python3 benchmarks/instancing/medians.py "$out" "$(git rev-parse --short HEAD)" > "$out/README.md"
cat "$out/README.md"
