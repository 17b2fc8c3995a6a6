#!/usr/bin/env bash
# BVH build time: `clpath bench build` (median of 3 builds, wall and CPU time,
# Mtris/s, SAH cost) on bunny and room:1003542 with 2 threads, repeated in
# ROUNDS rounds. On a shared machine, other builders' runs can be interleaved
# with clpath's so that both see the same load:
#   BASELINE=path/to/older/clpath  also times that binary in every round (before/after);
#   INTERLEAVE='command'           runs this command before clpath in every round and scene, with
#                                  SCENE set to the scene (output in the log).
# Usage: benchmarks/bvh_build/run.sh [RESULT_DIR_NAME] [BUILD_DIR]
#   writes benchmarks/results/RESULT_DIR_NAME/bvh-build/{log.txt,runs.csv}
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-xeon-2core}
B=${2:-$ROOT/build}
CLPATH=$B/clpath
OUT=$ROOT/benchmarks/results/$DEV_DIR/bvh-build
ROUNDS=${ROUNDS:-3}
THREADS=${THREADS:-2}
SCENES=${SCENES:-"$ROOT/scenes/bunny.json room:1003542"}
mkdir -p "$OUT"
LOG=$OUT/log.txt
{
  echo "== date: $(date -u +%FT%TZ)  commit: $(git -C "$ROOT" rev-parse --short HEAD)  host: $(hostname)"
  echo "== cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), $(nproc) cores"
  echo "== load before: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$LOG"
echo "round,binary,scene,triangles,threads,runs,median_ms,min_ms,max_ms,mtris_per_s,sah_cost,nodes,leaves,depth,load1" > "$OUT/runs.csv"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for round in $(seq 1 "$ROUNDS"); do
  for scene in $SCENES; do
    if [ -n "${INTERLEAVE:-}" ]; then
      echo "== round $round: $INTERLEAVE" | tee -a "$LOG"
      SCENE=$scene bash -c "$INTERLEAVE" 2>&1 | tee -a "$LOG"
    fi
    for bin in "$CLPATH" ${BASELINE:-}; do
      label=clpath; [ "$bin" != "$CLPATH" ] && label=baseline
      echo "== round $round: $label $scene (load $(cut -d' ' -f1 /proc/loadavg))" | tee -a "$LOG"
      load=$(cut -d' ' -f1 /proc/loadavg)
      "$bin" bench build "$scene" --threads "$THREADS" --repeat 3 --csv "$tmp/run.csv" 2>&1 | tee -a "$LOG"
      [ -f "$tmp/run.csv" ] && tail -n +2 "$tmp/run.csv" | sed "s/^/$round,$label,/; s/\$/,$load/" >> "$OUT/runs.csv"
      rm -f "$tmp/run.csv"
    done
  done
done
echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$LOG"
echo "run.sh: wrote $OUT/log.txt and $OUT/runs.csv"
