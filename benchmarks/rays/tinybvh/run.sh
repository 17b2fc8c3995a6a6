#!/usr/bin/env bash
# Traces the ray batches clpath saved (clpath bench rays SCENE --save-rays RAYS_DIR)
# with tinybvh's OpenCL kernels on the same scene's triangles:
#   TINYBVH_DIR=path/to/tinybvh benchmarks/rays/tinybvh/run.sh SCENE RAYS_DIR [tinybvh_rays options]
# The triangles come from `clpath export SCENE` (kept in RAYS_DIR/scene/ for
# later runs); the harness is built by build.sh when missing or older than its
# source. Options after RAYS_DIR go to the harness (tinybvh_rays --help).
# Environment: CLPATH (default build/clpath), HARNESS (default build/tinybvh-rays/tinybvh_rays).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
: "${TINYBVH_DIR:?set TINYBVH_DIR to a tinybvh checkout (see benchmarks/rays/tinybvh/build.sh)}"
[ $# -ge 2 ] || { echo "usage: TINYBVH_DIR=... $0 SCENE RAYS_DIR [tinybvh_rays options]" >&2; exit 2; }
SCENE=$1 RAYS=$2
shift 2
CLPATH=${CLPATH:-$ROOT/build/clpath}
HARNESS=${HARNESS:-$ROOT/build/tinybvh-rays/tinybvh_rays}
[ -d "$RAYS" ] || { echo "run.sh: error: $RAYS: no such folder (clpath bench rays SCENE --save-rays $RAYS first)" >&2; exit 1; }
stale=0
for f in "$HERE"/tinybvh_rays.cpp "$HERE"/*.hpp "$TINYBVH_DIR/tiny_bvh.h"; do [ "$f" -nt "$HARNESS" ] && stale=1; done
if [ ! -x "$HARNESS" ] || [ "$stale" = 1 ]; then
  "$HERE/build.sh" "$HARNESS" >&2
fi
OBJ=$RAYS/scene/scene.obj
if [ ! -f "$OBJ" ] || [ "$(cat "$RAYS/scene/source" 2>/dev/null)" != "$SCENE" ]; then
  rm -f "$RAYS/scene/source"
  "$CLPATH" export "$SCENE" "$RAYS/scene/scene.json" >&2
  echo "$SCENE" > "$RAYS/scene/source"
fi
# clpath export's first line: "# clpath export of 'NAME' from SCENE: N triangles, ..."
TRIANGLES=$(head -1 "$OBJ" | sed -n 's/.*: \([0-9]*\) triangles.*/\1/p')
exec "$HARNESS" --obj "$OBJ" --rays "$RAYS" --tinybvh "$TINYBVH_DIR" ${TRIANGLES:+--triangles "$TRIANGLES"} "$@"
