#!/usr/bin/env bash
# Equal-time error of the two light samplers (docs/light-bvh.md): clpath's
# default estimator with lights picked in proportion to power, then by the
# light BVH (bench convergence --configs lights-power,lights-bvh), ROUNDS
# times per scene; summary.py takes each round's efficiency ratio,
# 1/(MSE x time) of the light BVH over power at the last point (the squared
# error power would need in the same time, divided by the light BVH's), and
# reports the median.
#   room-lamp-sky     a lamp in a closed room under a bright sky
#   city:10000        2 x 10^4 small emissive triangles (many lights)
#   glass-in-glass    a lamp sealed in glass under a sky: no pick helps (Auto keeps power; the light BVH forced)
#   cornell-classic   one lamp: Auto keeps power; the light BVH forced, to see what it costs there
# References: clpath with the light BVH forced, 32768 spp at 64x48 (64x64 for
# cornell-classic), made into REFS on first use (an unbiased estimator the
# Mitsuba agreement tests check; its variance is 1/32 of a 1024-spp run's).
#
# Usage: benchmarks/light_sampler/run.sh [BUILD_DIR] [OUT] [ROUNDS] [MAX_SPP] [REFS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$root/build}; OUT=${2:-$root/benchmarks/results/pocl-epyc-2core/light-sampler}
ROUNDS=${3:-3}; MAX_SPP=${4:-1024}; REFS=${5:-$OUT/references}
B=$(cd "$B" && pwd); mkdir -p "$OUT" "$REFS"; OUT=$(cd "$OUT" && pwd); REFS=$(cd "$REFS" && pwd)
cd "$root"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo none)

# name  scene  width  height
scenes=(
  "room-lamp-sky   scenes/room-lamp-sky.json       64 48"
  "city-10000      city:10000                      64 48"
  "glass-in-glass  scenes/hard/glass-in-glass.json 64 48"
  "cornell-classic scenes/cornell-classic.json     64 64"
)
{
  echo "commit $commit, $(date -u +%FT%TZ), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
  "$B/clpath" devices 2>/dev/null | head -3 || true
} > "$OUT/log.txt"
for s in "${scenes[@]}"; do
  read -r name scene w h <<<"$s"
  ref=$REFS/$name.exr
  if [ ! -f "$ref" ]; then
    echo "reference $name: 32768 spp" >> "$OUT/log.txt"
    "$B/clpath" render "$scene" --spp 32768 --width "$w" --height "$h" --light-sampler bvh -o "$ref" --quiet >> "$OUT/log.txt"
  fi
  for r in $(seq 1 "$ROUNDS"); do
    dir=$OUT/$name/round$r; mkdir -p "$dir"
    "$B/clpath" bench convergence "$scene" --reference "$ref" --configs lights-power,lights-bvh --max-spp "$MAX_SPP" \
      --csv "$dir/convergence.csv" --md "$dir/convergence.md" >> "$OUT/log.txt" 2>&1
  done
done
python3 "$root/benchmarks/light_sampler/summary.py" "$OUT" "$commit" > "$OUT/README.md"
cat "$OUT/README.md"
