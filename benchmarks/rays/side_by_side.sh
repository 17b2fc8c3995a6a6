#!/usr/bin/env bash
# clpath's ray batches against tinybvh's OpenCL kernels on the same rays and the
# same OpenCL device, interleaved: in every round and scene, `clpath bench rays`
# (with its Embree baseline) saves its batches, then the tinybvh harness traces
# them (benchmarks/rays/tinybvh/), with clpath's own kernels paired launch by
# launch in its process (--paired), the comparison a drifting machine allows.
# Writes run files, medians and a README to
# benchmarks/results/RESULT_DIR_NAME/rays-tinybvh/.
#
#   git clone https://github.com/jbikker/tinybvh /some/where/tinybvh   (not into this repository)
#   TINYBVH_DIR=/some/where/tinybvh benchmarks/rays/side_by_side.sh [RESULT_DIR_NAME] [BUILD_DIR]
#
# RESULT_DIR_NAME defaults to pocl-xeon-2core, BUILD_DIR to build/ (which must hold clpath).
# Environment: ROUNDS (3), LAUNCHES (timed launches per batch, 5), SCENES ("scenes/bunny.json room:1003542"),
# LAYOUTS (tinybvh's: ailalaine,gpu4way,cwbvh), DEVICE (OpenCL device name part; default: the first),
# WORK (scratch folder for rays and OBJs, about 250 MB per scene; default: a temporary folder, removed after).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-xeon-2core}
B=${2:-$ROOT/build}
: "${TINYBVH_DIR:?set TINYBVH_DIR to a tinybvh checkout (git clone https://github.com/jbikker/tinybvh)}"
TINYBVH_DIR=$(cd "$TINYBVH_DIR" && pwd)
CLPATH=$B/clpath
HARNESS=$B/tinybvh-rays/tinybvh_rays
ROUNDS=${ROUNDS:-3}
LAUNCHES=${LAUNCHES:-5}
SCENES=${SCENES:-"$ROOT/scenes/bunny.json room:1003542"}
LAYOUTS=${LAYOUTS:-ailalaine,gpu4way,cwbvh}
OUT=$ROOT/benchmarks/results/$DEV_DIR/rays-tinybvh
[ -x "$CLPATH" ] || { echo "side_by_side.sh: error: $CLPATH: no clpath build there" >&2; exit 1; }
if [ -n "${WORK:-}" ]; then
  mkdir -p "$WORK"
else
  WORK=$(mktemp -d)
  trap 'rm -rf "$WORK"' EXIT
fi
mkdir -p "$OUT"
"$ROOT/benchmarks/rays/tinybvh/build.sh" "$HARNESS"
DEVICE_ARGS=()
HARNESS_DEVICE=()
if [ -n "${DEVICE:-}" ]; then DEVICE_ARGS=(--device "$DEVICE"); HARNESS_DEVICE=(--device "$DEVICE"); fi

LOG=$OUT/log.txt
load1() { cut -d' ' -f1 /proc/loadavg; }
# Prefixes every data row of CSV file $1 with "$2," (round,load1,...) and appends them to $3.
append_rows() { tail -n +2 "$1" | sed "s/^/$2,/" >> "$3"; }
{
  echo "== date: $(date -u +%FT%TZ)  clpath commit: $(git -C "$ROOT" rev-parse --short HEAD)  host: $(hostname)"
  echo "== tinybvh: $TINYBVH_DIR at $(git -C "$TINYBVH_DIR" rev-parse HEAD 2>/dev/null || echo 'unknown commit')"
  echo "== cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores"
  echo "== rounds $ROUNDS, launches $LAUNCHES, scenes: $SCENES, tinybvh layouts: $LAYOUTS"
  echo "== uptime before: $(uptime)"
} | tee "$LOG"
DATE_START=$(date -u '+%Y-%m-%d %H:%M UTC')
rm -f "$OUT/clpath-runs.csv" "$OUT/tinybvh-runs.csv"
for round in $(seq 1 "$ROUNDS"); do
  i=0
  for scene in $SCENES; do
    i=$((i + 1))
    rays=$WORK/rays-$i
    mkdir -p "$rays"
    l=$(load1)
    echo "== round $round: clpath bench rays $scene (load $l)" | tee -a "$LOG"
    rm -f "$WORK/clpath.csv"
    # Exit status 3 (a hit that disagrees with the CPU check) still leaves a CSV to record.
    "$CLPATH" bench rays "$scene" --launches "$LAUNCHES" --save-rays "$rays" --csv "$WORK/clpath.csv" \
      "${DEVICE_ARGS[@]}" 2>&1 | tee -a "$LOG" || true
    [ -f "$WORK/clpath.csv" ] || { echo "side_by_side.sh: error: clpath bench rays $scene wrote no CSV" | tee -a "$LOG" >&2; exit 1; }
    [ -f "$OUT/clpath-runs.csv" ] || { printf 'round,load1,'; head -1 "$WORK/clpath.csv"; } > "$OUT/clpath-runs.csv"
    append_rows "$WORK/clpath.csv" "$round,$l" "$OUT/clpath-runs.csv"
    # The rays are the same in every round (fixed camera, seed and kernels): their checksums show it.
    (cd "$rays" && sha256sum primary.rays shadow.rays diffuse.rays) | sed "s/^/== round $round rays: /" | tee -a "$LOG"
    name=$(awk -F, 'NR == 2 { print $2 }' "$WORK/clpath.csv")
    tris=$(awk -F, 'NR == 2 { print $3 }' "$WORK/clpath.csv")
    l=$(load1)
    echo "== round $round: tinybvh on the same rays, $scene (load $l)" | tee -a "$LOG"
    rm -f "$WORK/tinybvh.csv"
    TINYBVH_DIR=$TINYBVH_DIR CLPATH=$CLPATH HARNESS=$HARNESS "$ROOT/benchmarks/rays/tinybvh/run.sh" "$scene" "$rays" \
      --launches "$LAUNCHES" --layouts "$LAYOUTS" --label "$name" --triangles "$tris" --csv "$WORK/tinybvh.csv" --paired \
      "${HARNESS_DEVICE[@]}" 2>&1 | grep -v '^[0-9]* warnings\? generated\.$' | tee -a "$LOG"
    [ -f "$WORK/tinybvh.csv" ] || { echo "side_by_side.sh: error: the tinybvh harness wrote no CSV" | tee -a "$LOG" >&2; exit 1; }
    [ -f "$OUT/tinybvh-runs.csv" ] || { printf 'round,load1,'; head -1 "$WORK/tinybvh.csv"; } > "$OUT/tinybvh-runs.csv"
    append_rows "$WORK/tinybvh.csv" "$round,$l" "$OUT/tinybvh-runs.csv"
  done
done
echo "== uptime after: $(uptime)" | tee -a "$LOG"

META=$WORK/meta.txt
{
  echo "date_start=$DATE_START"
  echo "date_end=$(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "commit=$(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- host kernels || echo ' (with uncommitted changes)')"
  echo "tinybvh_commit=$(git -C "$TINYBVH_DIR" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "tinybvh_version=$(sed -n 's/^#define TINY_BVH_VERSION_\(MAJOR\|MINOR\|SUB\)[[:space:]]*\([0-9]*\).*/\2/p' "$TINYBVH_DIR/tiny_bvh.h" | paste -sd.)"
  echo "tinybvh_origin=$(git -C "$TINYBVH_DIR" remote get-url origin 2>/dev/null | sed 's#^/.*#a local clone of github.com/jbikker/tinybvh#')"
  echo "device=$(sed -n '2p' "$OUT/clpath-runs.csv" | cut -d, -f3)"
  echo "platform=$(grep -m1 '^device: ' "$LOG" | sed 's/.* (\(OpenCL .*\))$/\1/')"
  echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "cores=$(nproc)"
  echo "rounds=$ROUNDS"
  echo "launches=$LAUNCHES"
  echo "notes=$ROOT/benchmarks/rays/tinybvh/results_notes.md"
} > "$META"
python3 "$ROOT/benchmarks/rays/tinybvh/summarise.py" "$OUT" "$META"
echo "side_by_side.sh: wrote $OUT/{README.md,summary.csv,clpath-runs.csv,tinybvh-runs.csv,log.txt}"
