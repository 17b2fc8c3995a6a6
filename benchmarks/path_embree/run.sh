#!/usr/bin/env bash
# Path tracing against Embree: `clpath bench path` (clpath's renderer on the
# OpenCL device and an Embree 3 path tracer with the same estimator on every
# hardware thread, Embree in its default mode and robust, interleaved rounds,
# images checked to agree) on the
# point-light Cornell box, cornell-classic (area light, NEE + MIS) and bunny
# (70k triangles, shading normals, two-sided area light), at
# 512x512 and depth 4 without Russian roulette.
# Usage: benchmarks/path_embree/run.sh [RESULT_DIR_NAME] [BUILD_DIR]
#   writes benchmarks/results/RESULT_DIR_NAME/path-embree/{README.md,<scene>.txt,<scene>.csv}
# Environment: ROUNDS (3), SPP (16), DEPTH (4), SIZE (512), DEVICE (OpenCL device; default: the first),
#   SCENES ("scenes/cornell-point.json scenes/cornell-classic.json scenes/bunny.json"), NOTE (a line on the machine's
#   state for the README, e.g. "shared machine": the load averages are recorded either way).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-xeon-2core}
B=${2:-$ROOT/build}
CLPATH=$B/clpath
OUT=$ROOT/benchmarks/results/$DEV_DIR/path-embree
ROUNDS=${ROUNDS:-3}
SPP=${SPP:-16}
DEPTH=${DEPTH:-4}
SIZE=${SIZE:-512}
SCENES=${SCENES:-"$ROOT/scenes/cornell-point.json $ROOT/scenes/cornell-classic.json $ROOT/scenes/bunny.json"}
[ -x "$CLPATH" ] || { echo "run.sh: error: $CLPATH: no clpath build there" >&2; exit 1; }
DEVICE_ARGS=()
[ -n "${DEVICE:-}" ] && DEVICE_ARGS=(--device "$DEVICE")
mkdir -p "$OUT"
load() { cut -d' ' -f1-3 /proc/loadavg; }

DATE=$(date -u '+%Y-%m-%d %H:%M UTC')
COMMIT=$(git -C "$ROOT" rev-parse --short HEAD)
DIRTY=$(git -C "$ROOT" status --porcelain --untracked-files=no | grep -q . && echo " (with uncommitted changes)" || true)
CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) hardware threads"
ROWS=""
LOADS=""
COMMANDS=""
for scene in $SCENES; do
  name=$(basename "$scene" .json)
  before=$(load)
  cmd=("$CLPATH" bench path "$scene" --width "$SIZE" --height "$SIZE" --spp "$SPP" --max-depth "$DEPTH"
       --rounds "$ROUNDS" --csv "$OUT/$name.csv" "${DEVICE_ARGS[@]}")
  echo "== $name (load before: $before)"
  # The agreement check's verdict is part of the result: a disagreement is recorded, then reported.
  set +e
  "${cmd[@]}" > "$OUT/$name.txt" 2>&1
  rc=$?
  set -e
  after=$(load)
  cat "$OUT/$name.txt"
  LOADS+="- $name: load average $before before, $after after"$'\n'
  COMMANDS+="    clpath bench path ${scene#"$ROOT"/} --width $SIZE --height $SIZE --spp $SPP --max-depth $DEPTH --rounds $ROUNDS --csv $name.csv"$'\n'
  f=$OUT/$name.txt
  c_dev=$(sed -n 's/^clpath: \(.*\): median .*/\1/p' "$f")
  e_dev=$(sed -n 's/^Embree default mode: \(.*\): median .*/\1/p' "$f")
  r_dev=$(sed -n 's/^Embree robust mode: \(.*\): median .*/\1/p' "$f")
  c=$(sed -n 's/^clpath: .*: median \([0-9.]*\) Msamples\/s, \([0-9.]*\) Mrays\/s (\([0-9.]*\) rays per sample)/\1 | \2 | \3/p' "$f")
  e=$(sed -n 's/^Embree default mode: .*: median \([0-9.]*\) Msamples\/s, \([0-9.]*\) Mrays\/s (\([0-9.]*\) rays per sample)/\1 | \2/p' "$f")
  r=$(sed -n 's/^Embree robust mode: .*: median \([0-9.]*\) Msamples\/s, \([0-9.]*\) Mrays\/s (\([0-9.]*\) rays per sample)/\1 | \2/p' "$f")
  ratio=$(sed -n 's/^clpath\/Embree default mode: \([0-9.]*\) (Msamples\/s), \([0-9.]*\) (Mrays\/s).*/\1 | \2/p' "$f")
  ratio_r=$(sed -n 's/^clpath\/Embree robust mode: \([0-9.]*\) (Msamples\/s), \([0-9.]*\) (Mrays\/s).*/\1 | \2/p' "$f")
  agree=$(sed -n 's/^agreement with Embree \([a-z]*\) mode .*max |z| \([0-9.]*\); bound |z| <= \([0-9.]*\).*: \([A-Za-z]*\)$/\1: max \\|z\\| \2 (bound \3) \4/p' "$f" | paste -sd ';' - | sed 's/;/; /')
  ROWS+="| $name | $c | $e | $r | $ratio | $ratio_r | $agree |"$'\n'
  [ "$rc" -eq 0 ] || { echo "run.sh: error: clpath bench path exited $rc on $name (see $f)" >&2; FAILED=1; }
done

cat > "$OUT/README.md" <<MD
# Path tracing against Embree: \`clpath bench path\`

- Machine: ${NOTE:-(no note given)}
$LOADS- OpenCL device (clpath): $c_dev
- CPU baselines: $e_dev; and $r_dev
- CPU: $CPU
- Date: $DATE. Commit: $COMMIT$DIRTY.
- What runs: clpath's renderer (the \`path\` integrator: next-event estimation with MIS for area lights,
  cosine-weighted bounces; \`render --max-depth $DEPTH --rr none\`, the same kernels) and the Embree path
  tracer (host/bench/embree_path_tracer.cpp: the same estimator on the CPU, one path per sample, single rays)
  with Embree in its default mode (no \`RTC_SCENE_FLAG_ROBUST\`, as Embree's users and its own example
  renderers run it) and in robust mode (watertight, like clpath's kernels: the like-for-like guarantee),
  in $ROUNDS interleaved rounds of $SPP samples per pixel at ${SIZE}x$SIZE, after one warm-up sample each.
  clpath's time is its launches' wall time to completion, Embree's the wall time of its render (threads
  started and joined). Rays are counted as the kernels count them: every camera, bounce and shadow ray traced.
  Medians over the rounds; the ratio is the median of the per-round ratios. The default mode's ratio is
  the headline one.
- Agreement: the last round's images (independent random streams) compared by z-scores of the image
  mean and of 4x4 regions' means per channel, with the variance from Embree's per-pixel sample variance;
  clpath's against each Embree image, each bound keeping its false-failure rate below 5e-7
  (host/bench/path_agreement.hpp).
- Commands (full output in the \`.txt\` files, rounds in the \`.csv\` files):

$COMMANDS
| scene | clpath Msamples/s | clpath Mrays/s | clpath rays/sample | Embree default Msamples/s | Embree default Mrays/s | Embree robust Msamples/s | Embree robust Mrays/s | clpath/Embree default (samples) | clpath/Embree default (rays) | clpath/Embree robust (samples) | clpath/Embree robust (rays) | images |
|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|
$ROWS
MD
echo "run.sh: wrote $OUT/README.md"
[ -z "${FAILED:-}" ]
