#!/usr/bin/env bash
# What glTF and texture support cost, and how fast a million-triangle glTF loads.
#
#   render: path-traced rate (Msamples/s from the summary line, which leaves out
#     loading, the BVH build and kernel compilation) of
#     (a) scenes without textures (cornell-classic, bunny), specialised kernels
#         and --all-features, with this build and the older builds given;
#     (b) the textured scenes (scenes/textured, Suzanne) against the same
#         scenes with one grey diffuse material (scenes/*-plain.json here).
#   load: seconds to load room:1003542 (1,004,014 triangles) written as a .glb
#     and as a single-file .gltf (buffer as a base64 data URI) by obj_to_glb.py,
#     from the "loaded ... in X s" line of clpath render; with LOAD_BEFORE too.
#
# Every configuration runs once per round, rounds interleaved (REPS, default
# 3), so that all see the same machine load; the median is reported. A first,
# untimed round compiles every kernel (PoCL caches them).
#
# Usage: benchmarks/feature_cost/run.sh [render|load|all] [RESULT_DIR_NAME]
#   writes benchmarks/results/RESULT_DIR_NAME/feature-cost/ (default pocl-xeon-2core)
# Environment:
#   CLPATH       this build's binary (default build/clpath)
#   PRE_GLTF     a build of main before the glTF merge (a0af516), optional
#   PRE_SPLIT    a build of main before the material split (793641d), optional
#   LOAD_BEFORE  the binary whose load time is the "before" (default PRE_SPLIT)
#   REPS, SPP (16), WIDTH x HEIGHT (320 x 240), WORK (scratch folder for the glTF files)
#   QUICK=1      one round, no warm-up, tiny images and room:3000, results in OUT_DIR (CI runs this
#                so the script does not rot; its numbers mean nothing)
# Exits 1 when any run printed no result.
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
HERE=$ROOT/benchmarks/feature_cost
WHAT=${1:-all}
DEV_DIR=${2:-pocl-xeon-2core}
CLPATH=${CLPATH:-$ROOT/build/clpath}
PRE_GLTF=${PRE_GLTF:-}
PRE_SPLIT=${PRE_SPLIT:-}
LOAD_BEFORE=${LOAD_BEFORE:-$PRE_SPLIT}
REPS=${REPS:-3}
SPP=${SPP:-16}
WIDTH=${WIDTH:-320}
HEIGHT=${HEIGHT:-240}
WORK=${WORK:-/tmp/clpath-feature-cost}
ROOM=room:1003542
FIRST_ROUND=0  # round 0 is the untimed warm-up
OUT=$ROOT/benchmarks/results/$DEV_DIR/feature-cost
if [ -n "${QUICK:-}" ]; then
  REPS=1 SPP=1 WIDTH=16 HEIGHT=12 ROOM=room:3000 FIRST_ROUND=1 PRE_GLTF= PRE_SPLIT= LOAD_BEFORE=
  OUT=${OUT_DIR:?QUICK=1 needs OUT_DIR}
fi
failed=0
mkdir -p "$OUT" "$WORK"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

header() {
  echo "== date: $(date -u +%FT%TZ)  commit: $(git -C "$ROOT" rev-parse --short HEAD)  host: $(hostname)"
  echo "== cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), $(nproc) cores; device: $("$CLPATH" devices 2>&1 | grep -m1 '\[0\]')"
  echo "== binaries: this=$CLPATH pre_gltf=${PRE_GLTF:-none} pre_split=${PRE_SPLIT:-none} load_before=${LOAD_BEFORE:-none}"
  echo "== load before: $(cut -d' ' -f1-3 /proc/loadavg)  (the machine is shared: other users' builds and runs)"
}

# ---- render rates --------------------------------------------------------------
# One configuration per line: label|binary|scene|extra options
render_configs() {
  local b name
  for b in this:$CLPATH pre_split:$PRE_SPLIT pre_gltf:$PRE_GLTF; do
    name=${b%%:*}
    [ -n "${b#*:}" ] || continue
    for scene in cornell-classic bunny; do
      echo "$name|${b#*:}|$ROOT/scenes/$scene.json|"
      echo "$name|${b#*:}|$ROOT/scenes/$scene.json|--all-features"
    done
  done
  for b in this:$CLPATH pre_split:$PRE_SPLIT; do  # the build before glTF cannot read these scenes
    name=${b%%:*}
    [ -n "${b#*:}" ] || continue
    for scene in "$ROOT/scenes/textured/textured.json" "$HERE/scenes/textured-plain.json" \
                 "$HERE/scenes/suzanne-textured.json" "$HERE/scenes/suzanne-plain.json"; do
      echo "$name|${b#*:}|$scene|"
    done
  done
}

run_render() {
  local log=$OUT/render-log.txt csv=$OUT/render-runs.csv
  header | tee "$log"
  echo "== $SPP spp at ${WIDTH}x${HEIGHT}, path integrator, seed 1" | tee -a "$log"
  echo "round,binary,scene,options,render_s,msamples_per_s,load1" > "$csv"
  render_configs > "$tmp/configs"
  for round in $(seq "$FIRST_ROUND" "$REPS"); do
    while IFS='|' read -r label bin scene opts; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      # shellcheck disable=SC2086
      line=$("$bin" render "$scene" --spp "$SPP" --width "$WIDTH" --height "$HEIGHT" --seed 1 -q $opts \
               -o "$tmp/out.pfm" 2>&1 | grep '^summary:')
      [ "$round" = 0 ] && continue  # the warm-up round: kernels compiled and cached
      rs=$(sed -n 's/.* render_s=\([0-9.]*\).*/\1/p' <<< "$line")
      ms=$(sed -n 's/.* msamples_per_s=\([0-9.]*\).*/\1/p' <<< "$line")
      [ -n "$ms" ] || failed=$((failed + 1))
      echo "== round $round: $label $(basename "$scene") ${opts:-specialised}: ${ms:-FAILED} Msamples/s (load $load)" | tee -a "$log"
      echo "$round,$label,$(basename "$scene" .json),${opts:-specialised},$rs,$ms,$load" >> "$csv"
    done < "$tmp/configs"
  done
  echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$log"
  python3 "$HERE/summarise.py" render "$csv" > "$OUT/render-summary.md"
  cat "$OUT/render-summary.md"
}

# ---- glTF load time --------------------------------------------------------------
run_load() {
  local log=$OUT/load-log.txt csv=$OUT/load-runs.csv
  header | tee "$log"
  if [ -n "${QUICK:-}" ] || [ ! -s "$WORK/room.glb" ] || [ ! -s "$WORK/room.gltf" ]; then
    "$CLPATH" export "$ROOM" "$WORK/room-obj/room.json" | tee -a "$log"
    python3 "$HERE/obj_to_glb.py" "$WORK/room-obj/room.obj" "$WORK/room.glb" "$WORK/room.gltf" | tee -a "$log"
    rm -rf "$WORK/room-obj"
  fi
  echo "round,binary,file,load_s,triangles,load1" > "$csv"
  for round in $(seq "$FIRST_ROUND" "$REPS"); do
    for b in this:$CLPATH before:$LOAD_BEFORE; do
      [ -n "${b#*:}" ] || continue
      for f in room.glb room.gltf; do
        load=$(cut -d' ' -f1 /proc/loadavg)
        line=$("${b#*:}" render "$WORK/$f" --spp 1 --width 8 --height 8 --max-depth 0 -o "$tmp/l.pfm" 2>&1 |
               grep "^clpath: loaded ")
        [ "$round" = 0 ] && continue  # warm-up: the file in the page cache, kernels compiled
        s=$(sed -n 's/.* in \([0-9.]*\) s: .*/\1/p' <<< "$line")
        [ -n "$s" ] || failed=$((failed + 1))
        n=$(sed -n 's/.* s: \([0-9]*\) triangles.*/\1/p' <<< "$line")
        echo "== round $round: ${b%%:*} $f: ${s:-FAILED} s, $n triangles (load $load)" | tee -a "$log"
        echo "$round,${b%%:*},$f,$s,$n,$load" >> "$csv"
      done
    done
  done
  echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$log"
  python3 "$HERE/summarise.py" load "$csv" > "$OUT/load-summary.md"
  cat "$OUT/load-summary.md"
}

case $WHAT in
  render) run_render ;;
  load) run_load ;;
  all) run_render; run_load ;;
  *) echo "usage: $0 [render|load|all] [RESULT_DIR_NAME]" >&2; exit 2 ;;
esac
if [ "$failed" != 0 ]; then
  echo "$failed runs printed no result (see the logs in $OUT)" >&2
  exit 1
fi
