#!/usr/bin/env bash
# The portability gate's resource table: every program clpath builds for a GPU
# device (the covering set of host/render/kernel_programs.hpp and the programs
# of cornell and every bundled scene) compiled offline for NVIDIA sm_90 and AMD
# gfx90a and gfx1100 by `clpath kernels --report`, with each kernel's
# registers, stack/private bytes and spills. No GPU is needed.
#   BEFORE=DIR   also compiles the kernel files in DIR in place of the built-in
#                ones (clpath kernels --kernels DIR), e.g. an older commit's
#                kernels/, and tables both side by side.
#   JOBS=N       compiles at once (default: every core).
# Usage: benchmarks/gpu-compile/run.sh [BUILD_DIR]
#   writes benchmarks/results/gpu-compile/{README.md,resources.csv,log.txt}
#   (and before.csv with BEFORE).
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$ROOT/build}
CLPATH=$B/clpath
OUT=$ROOT/benchmarks/results/gpu-compile
JOBS=${JOBS:-$(nproc)}
mkdir -p "$OUT"
SCENES=$(cd "$ROOT" && find scenes -name '*.json' -o -name '*.gltf' | sort | sed "s|^|$ROOT/|")
LOG=$OUT/log.txt
{
  echo "== date: $(date -u +%FT%TZ)  commit: $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- kernels host || echo ' (with uncommitted changes)')"
  echo "== clpath kernels --report --covering cornell <every scenes/**/*.json and *.gltf> --jobs $JOBS"
} > "$LOG"
# shellcheck disable=SC2086
"$CLPATH" kernels --report --covering cornell $SCENES --jobs "$JOBS" --csv "$OUT/resources.csv" \
    > "$OUT/report.txt" 2>> "$LOG" || echo "== clpath kernels exited with status $?" >> "$LOG"
tail -n 1 "$OUT/report.txt" >> "$LOG"
rm -f "$OUT/report.txt"
before_args=()
if [ -n "${BEFORE:-}" ]; then
  echo "== before: the kernel files of $BEFORE" >> "$LOG"
  # shellcheck disable=SC2086
  "$CLPATH" kernels --report --covering cornell $SCENES --jobs "$JOBS" --kernels "$BEFORE" \
      --csv "$OUT/before.csv" > /dev/null 2>> "$LOG" || echo "== before: exited with status $?" >> "$LOG"
  before_args=(--before "$OUT/before.csv" --before-label "${BEFORE_LABEL:-before}")
fi
python3 "$ROOT/benchmarks/gpu-compile/summarize.py" "$OUT/resources.csv" --log "$LOG" "${before_args[@]}" \
    > "$OUT/README.md"
echo "wrote $OUT/README.md"
