#!/usr/bin/env bash
# The full scaling and ray-batch benchmarks on one device, with plots and a
# README naming the device, driver, date and commit:
#   benchmarks/scaling/run.sh DEVICE_DIR [DEVICE_SPEC] [BUILD_DIR]
# e.g. benchmarks/scaling/run.sh pocl-epyc-2core portable build
#      benchmarks/scaling/run.sh nvidia-h100 nvidia build-gpu
# Writes benchmarks/results/DEVICE_DIR/scaling/ and .../rays/.
# Environment: SCALING_MAX (largest scaling size, default 1e7), TIME_CAP
# (seconds, the flat structure's cap, default 60), RAY_LAUNCHES (default 5),
# ROOM_SIZES (closed-room sizes for the ray batches, default "1003542 3996202"),
# PLOT=0 to skip the plots (a machine without matplotlib; plot later with
# benchmarks/scaling/plot_scaling.py), SCALING=0 to run the ray batches only
# (the scaling folder is left as it is), NOTE (a line on the machine's state for the rays README),
# SCALING_ROUNDS (runs of bench scaling, default 3: the table gives each
# rate's median and its variation between the runs).
set -euo pipefail
DIR=${1:?usage: run.sh DEVICE_DIR [DEVICE_SPEC] [BUILD_DIR]}
SPEC=${2:-}
B=${3:-build}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CLPATH="$B/clpath"
[ -x "$CLPATH" ] || { echo "run.sh: $CLPATH is not built" >&2; exit 2; }
OUT="$ROOT/benchmarks/results/$DIR"
mkdir -p "$OUT/scaling" "$OUT/rays"
DEV=()
[ -n "$SPEC" ] && DEV=(--device "$SPEC")
MAX=${SCALING_MAX:-1e7}
CAP=${TIME_CAP:-60}
LAUNCHES=${RAY_LAUNCHES:-5}
ROOMS=${ROOM_SIZES:-"1003542 3996202"}
BUNNY_OBJ=/usr/share/glmark2/models/bunny.obj

device_line=$("$CLPATH" devices 2>/dev/null | grep -i -- "${SPEC:-.}" | grep "\[" | head -n 1 | sed "s/^ *//" || true)
commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
dirty=$(git -C "$ROOT" status --porcelain --untracked-files=no 2>/dev/null | grep -q . && echo " (with uncommitted changes)" || true)
date=$(date -u +%FT%TZ)
header() {
  echo "- device: \`$device_line\`"
  echo "- date: $date; commit: $commit$dirty; host: $(uname -n), $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo) memory"
}

# --- scaling ---------------------------------------------------------------------
start=$(date +%s)
ROUNDS=${SCALING_ROUNDS:-3}
if [ "${SCALING:-1}" != 0 ]; then
  scaling_load_before=$(cut -d' ' -f1-3 /proc/loadavg)
  : > "$OUT/scaling/log.txt"
  rm -f "$OUT"/scaling/scaling-run*.csv
  for r in $(seq 1 "$ROUNDS"); do
    echo "== run $r of $ROUNDS" | tee -a "$OUT/scaling/log.txt"
    "$CLPATH" bench scaling "${DEV[@]}" --max "$MAX" --time-cap "$CAP" \
      --csv "$OUT/scaling/scaling-run$r.csv" 2>&1 | tee -a "$OUT/scaling/log.txt"
  done
  if [ "$ROUNDS" -ge 2 ]; then
    "${PYTHON:-/usr/bin/python3}" "$ROOT/benchmarks/scaling/summarize_rounds.py" "$OUT/scaling/scaling.csv" \
      "$OUT/scaling/scaling.md" "$OUT"/scaling/scaling-run*.csv
  else
    cp "$OUT/scaling/scaling-run1.csv" "$OUT/scaling/scaling.csv"
    sed -n '/^| triangles/,$p' "$OUT/scaling/log.txt" > "$OUT/scaling/scaling.md"
  fi
  scaling_load_after=$(cut -d' ' -f1-3 /proc/loadavg)
fi
scaling_s=$(( $(date +%s) - start ))

# --- ray batches -----------------------------------------------------------------
start=$(date +%s)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
: > "$OUT/rays/log.txt"
rays() {  # name, then clpath bench rays arguments
  local name=$1; shift
  echo "== $name" | tee -a "$OUT/rays/log.txt"
  # A disagreement with the CPU reference exits 3: recorded in the log and the table, the other runs go on.
  "$CLPATH" bench rays "$@" "${DEV[@]}" --launches "$LAUNCHES" --csv "$OUT/rays/$name.csv" 2>&1 | tee -a "$OUT/rays/log.txt" ||
    echo "run.sh: bench rays $name exited with status $?" | tee -a "$OUT/rays/log.txt"
}
rays cornell-bvh cornell --accel bvh
rays cornell-flat cornell --accel flat
rays bunny-room "$ROOT/scenes/bunny.json"
# The bare bunny, framed as a bare mesh is by default (tinybvh's published bunny test has about a third of its primary rays hit).
[ -f "$BUNNY_OBJ" ] && rays bunny-bare "$BUNNY_OBJ"
for n in $ROOMS; do rays "room-$n" "room:$n"; done
rays_s=$(( $(date +%s) - start ))
# One table of every ray run.
{ head -n 1 "$OUT"/rays/cornell-bvh.csv; for f in "$OUT"/rays/*.csv; do [ "$(basename "$f")" = all.csv ] || tail -n +2 "$f"; done; } > "$OUT/rays/all.csv.tmp"
mv "$OUT/rays/all.csv.tmp" "$OUT/rays/all.csv"

if [ "${PLOT:-1}" != 0 ] && [ "${SCALING:-1}" != 0 ]; then
  "${PYTHON:-/usr/bin/python3}" "$ROOT/benchmarks/scaling/plot_scaling.py" "$OUT/scaling/scaling.csv" "$OUT/scaling"
fi

[ "${SCALING:-1}" != 0 ] && {
  echo "# Scaling benchmark: \`clpath bench scaling\`"
  echo
  header
  echo "- command: \`clpath bench scaling ${DEV[*]} --max $MAX --time-cap $CAP\`, run $ROUNDS times (benchmarks/scaling/run.sh), $scaling_s s in all;"
  echo "  load average before and after: $scaling_load_before / $scaling_load_after.${NOTE:+ $NOTE}"
  echo "- scenes: \`scaling:N\` (the thesis room around one bumpy UV sphere); ray batches at 480x320 pixels x 16 samples"
  echo "  (2.46 million rays; one warm-up and 5 timed launches, Mrays/s from the median launch), the path column a 320x240"
  echo "  render at 4 samples per pixel by the renderer \`clpath render\` runs (path integrator; after a warm-up render,"
  echo "  the median of three); CPU check of 4096"
  echo "  evenly spaced rays per batch. Each entry: the median of the runs, with their coefficient of variation."
  echo "  Embree 3 traces the BVH rows' batches in the same run on the same cores, in its default mode (as its users run"
  echo "  it), its rate from its median pass: its own fall with the scene's size, read beside clpath's."
  echo "  Every run's table: scaling-run*.csv; output: log.txt."
  echo "- the flat structure (one box per object, the thesis renderer's) stops when its next size is predicted to take"
  echo "  longer than $CAP s; sizes above the memory budget (80 % of MemAvailable) are skipped; both say so in the table."
  echo
  cat "$OUT/scaling/scaling.md"
  echo
  echo "![rays per second against triangles](rays_vs_triangles.png)"
  echo "![build time against triangles](build_time.png)"
} > "$OUT/scaling/README.md"

{
  echo "# Ray-batch benchmark: \`clpath bench rays\`"
  echo
  header
  echo "- 480x320 pixels x 16 samples (4x4 sub-pixel grid), rays in 4x4-pixel tiles; primary (closest hit), shadow"
  echo "  to the point light from the primary hits (any hit), diffuse (cosine) from the primary hits (closest hit);"
  echo "  one warm-up + $LAUNCHES timed launches, kernel time from OpenCL profiling events, Mrays/s from the mean."
  echo "- secondary batches hold one ray per primary hit (misses make none)."
  echo "- Embree 3 traces every batch on the same cores in the same run, twice: in its default mode (as its users run"
  echo "  it; its ratio first) and in its robust mode (\`RTC_SCENE_FLAG_ROBUST\`, watertight like clpath: like for like)."
  echo "- load average before and after: $load_before / $(cut -d' ' -f1-3 /proc/loadavg).${NOTE:+ $NOTE}"
  echo "- $rays_s s in all. Full output: log.txt; every run: all.csv."
  echo
  echo "| scene | triangles | structure | batch | rays | hits | Mrays/s (mean) | CPU check: rays | identical % | ties | at the origin | mismatched | Embree default Mrays/s | **clpath/Embree default** | Embree robust Mrays/s | clpath/Embree robust | Embree mismatched (default, robust) |"
  echo "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  tail -n +2 "$OUT/rays/all.csv" | awk -F, '{printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | **%s** | %s | %s | %s, %s |\n", $2, $3, $4, $5, $9, $10, $14, $15, $16, $17, $18, $19, $22, $23, $26, $27, $24, $28}'
} > "$OUT/rays/README.md"
echo "run.sh: wrote $OUT/scaling and $OUT/rays"
