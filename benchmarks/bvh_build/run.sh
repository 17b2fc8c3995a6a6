#!/usr/bin/env bash
# BVH build time: `clpath bench build` (median of 3 builds, wall and CPU time,
# Mtris/s, SAH cost) on bunny and room:1003542 with 2 threads, side by side
# with tinybvh's builders on the same triangles, in ROUNDS rounds; the order
# of the two programs alternates from round to round, so both meet about the
# same load. One command:
#   git clone https://github.com/jbikker/tinybvh /some/where/tinybvh   (not into this repository)
#   TINYBVH_DIR=/some/where/tinybvh benchmarks/bvh_build/run.sh [RESULT_DIR_NAME] [BUILD_DIR]
# writes benchmarks/results/RESULT_DIR_NAME/bvh-build/{log.txt,runs.csv,tinybvh-runs.csv,README.md}.
# The tinybvh harness (benchmarks/bvh_build/tinybvh/) is compiled as tinybvh's
# own CMake file compiles it (-march=native), so BuildDefault is what tinybvh's
# users get on this CPU (BuildAVX where AVX is there).
# Environment: ROUNDS (3), THREADS (2), SCENES ("scenes/bunny.json room:1003542"),
#   TINYBVH_BUILDERS (default,build: BuildDefault and the reference Build; also avx, hq),
#   TINYBVH_DIR unset: clpath alone (as before);
#   BASELINE=path/to/older/clpath  also times that binary in every round (before/after);
#   NOTE  a line on the machine's state for the README; one starting "shared" (e.g. "shared with
#         other builds") marks the run as on a shared machine whatever the load average says.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-epyc-2core}
B=${2:-$ROOT/build}
CLPATH=$B/clpath
OUT=$ROOT/benchmarks/results/$DEV_DIR/bvh-build
ROUNDS=${ROUNDS:-3}
THREADS=${THREADS:-2}
SCENES=${SCENES:-"$ROOT/scenes/bunny.json room:1003542"}
TINYBVH_BUILDERS=${TINYBVH_BUILDERS:-default,build}
HARNESS=$B/tinybvh-build/tinybvh_build
[ -x "$CLPATH" ] || { echo "run.sh: error: $CLPATH: no clpath build there" >&2; exit 1; }
mkdir -p "$OUT"
LOG=$OUT/log.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -n "${TINYBVH_DIR:-}" ]; then
  "$ROOT/benchmarks/bvh_build/tinybvh/build.sh" "$HARNESS" || exit 1
fi
DATE_START=$(date -u '+%Y-%m-%d %H:%M UTC')
{
  echo "== date: $(date -u +%FT%TZ)  commit: $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- host || echo ' (with uncommitted changes in host/)')  host: $(hostname)"
  echo "== cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores"
  [ -n "${TINYBVH_DIR:-}" ] && echo "== tinybvh: $TINYBVH_DIR at $(git -C "$TINYBVH_DIR" rev-parse --short HEAD 2>/dev/null || echo 'unknown commit'), builders $TINYBVH_BUILDERS"
  echo "== load before: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$LOG"
echo "round,binary,scene,triangles,threads,runs,median_ms,min_ms,max_ms,mtris_per_s,sah_cost,nodes,leaves,depth,load1" > "$OUT/runs.csv"
rm -f "$OUT/tinybvh-runs.csv"
[ -n "${TINYBVH_DIR:-}" ] &&
  echo "round,scene,triangles,builder,runs,median_ms,min_ms,max_ms,mtris_per_s,sah_cost,nodes,leaves,max_leaf,depth,load1" > "$OUT/tinybvh-runs.csv"

run_clpath() {  # round scene
  for bin in "$CLPATH" ${BASELINE:-}; do
    label=clpath; [ "$bin" != "$CLPATH" ] && label=baseline
    load=$(cut -d' ' -f1 /proc/loadavg)
    echo "== round $1: $label $2 (load $load)" | tee -a "$LOG"
    rm -f "$tmp/run.csv"
    "$bin" bench build "$2" --threads "$THREADS" --repeat 3 --csv "$tmp/run.csv" 2>&1 | tee -a "$LOG"
    [ -f "$tmp/run.csv" ] && tail -n +2 "$tmp/run.csv" | sed "s/^/$1,$label,/; s/\$/,$load/" >> "$OUT/runs.csv"
  done
}
run_tinybvh() {  # round scene index
  obj=$tmp/scene-$3/scene.obj
  if [ ! -f "$obj" ]; then
    mkdir -p "$tmp/scene-$3"
    "$CLPATH" export "$2" "$tmp/scene-$3/scene.json" >> "$LOG" 2>&1 ||
      { echo "run.sh: error: clpath export $2 failed" | tee -a "$LOG" >&2; exit 1; }
  fi
  name=$(basename "$2" .json)  # the summary pairs the two programs' rows by triangle count
  load=$(cut -d' ' -f1 /proc/loadavg)
  echo "== round $1: tinybvh $2 (load $load)" | tee -a "$LOG"
  rm -f "$tmp/tb.csv"
  "$HARNESS" --obj "$obj" --builders "$TINYBVH_BUILDERS" --label "$name" --csv "$tmp/tb.csv" 2>&1 | tee -a "$LOG"
  [ -f "$tmp/tb.csv" ] && tail -n +2 "$tmp/tb.csv" | sed "s/^/$1,/; s/\$/,$load/" >> "$OUT/tinybvh-runs.csv"
}

for round in $(seq 1 "$ROUNDS"); do
  i=0
  for scene in $SCENES; do
    i=$((i + 1))
    if [ -z "${TINYBVH_DIR:-}" ]; then
      run_clpath "$round" "$scene"
    elif [ $((round % 2)) = 1 ]; then
      run_tinybvh "$round" "$scene" "$i"; run_clpath "$round" "$scene"
    else
      run_clpath "$round" "$scene"; run_tinybvh "$round" "$scene" "$i"
    fi
  done
done
echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$LOG"
if [ -n "${TINYBVH_DIR:-}" ]; then
  {
    echo "date_start=$DATE_START"
    echo "date_end=$(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "commit=$(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- host || echo ' (with uncommitted changes in host/)')"
    echo "tinybvh_commit=$(git -C "$TINYBVH_DIR" rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
    echo "cores=$(nproc)"
    echo "threads=$THREADS"
    echo "rounds=$ROUNDS"
    echo "note=${NOTE:-}"
  } > "$tmp/meta"
  python3 "$ROOT/benchmarks/bvh_build/summarise.py" "$OUT" "$tmp/meta"
fi
echo "run.sh: wrote $OUT"
