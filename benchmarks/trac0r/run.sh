#!/usr/bin/env bash
# Path tracing side by side with trac0r (2016), the thesis path tracer clpath
# began as, on trac0r's own scene (its viewer's room, 800x640): trac0r's
# OpenMP build as its CMake file builds it (-O3 -march=native -fopenmp), and
# clpath's `render` on the same room (scenes/cornell-thesis-diffuse.json,
# docs/thesis-scene.md) with its default settings and with trac0r's estimator
# (BSDF sampling only, depth roulette, 10 bounces), in ROUNDS interleaved
# rounds. One command:
#   git clone --recursive https://github.com/svenstaro/trac0r /some/where/trac0r   (not into this repository)
#   TRAC0R_DIR=/some/where/trac0r benchmarks/trac0r/run.sh [RESULT_DIR_NAME] [BUILD_DIR]
# writes benchmarks/results/RESULT_DIR_NAME/trac0r/{README.md,runs.csv,log.txt}.
# trac0r is an SDL viewer: it needs SDL2, SDL2_image and SDL2_ttf
# (tools/install-deps.sh) and a display, here a private Xvfb. Its -fN mode
# renders N + 1 frames of one sample per pixel, saves the last and quits; the
# process is timed at two frame counts and the difference divided by the
# extra frames, so start-up (X, fonts, the scene) cancels out. A frame is
# what a trac0r user waits for: the samples, then tone mapping and the
# window's update (measured apart in the README).
# Environment: ROUNDS (3), FRAMES ("2 12": the two -f values), SPP (clpath's
#   samples per pixel, 16), DEVICE (clpath's OpenCL device), NOTE (a line on
#   the machine's state for the README).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-epyc-2core}
B=$(cd "${2:-$ROOT/build}" && pwd)
CLPATH=$B/clpath
ROUNDS=${ROUNDS:-3}
FRAMES=${FRAMES:-"2 12"}
SPP=${SPP:-16}
SCENE=$ROOT/scenes/cornell-thesis-diffuse.json
OUT=$ROOT/benchmarks/results/$DEV_DIR/trac0r
T0=$B/trac0r-omp
[ -x "$CLPATH" ] || { echo "run.sh: error: $CLPATH: no clpath build there" >&2; exit 1; }
[ -n "${TRAC0R_DIR:-}" ] && [ -f "$TRAC0R_DIR/CMakeLists.txt" ] ||
  { echo "run.sh: error: set TRAC0R_DIR to a recursive clone of https://github.com/svenstaro/trac0r" >&2; exit 1; }
[ -f "$TRAC0R_DIR/external/glm/glm/glm.hpp" ] ||
  { echo "run.sh: error: $TRAC0R_DIR has no submodules (git submodule update --init)" >&2; exit 1; }
command -v Xvfb > /dev/null || { echo "run.sh: error: Xvfb not found (Debian: apt-get install xvfb)" >&2; exit 1; }
read -r F1 F2 <<< "$FRAMES"
[ "$F2" -gt "$F1" ] || { echo "run.sh: error: FRAMES must be two counts, the second larger" >&2; exit 1; }
DEV=()
[ -n "${DEVICE:-}" ] && DEV=(--device "$DEVICE")

# trac0r's own flags (-O3 -march=native -fopenmp -Werror ...). GCC 12 warns
# about a loop variable copy that GCC 5 did not, and -Werror stops the build;
# that one warning stays a warning. Code generation is unchanged.
mkdir -p "$T0"
cmake -S "$TRAC0R_DIR" -B "$T0" -DCMAKE_CXX_FLAGS="-Wno-error=range-loop-construct" > "$T0/configure.log" 2>&1 ||
  { cat "$T0/configure.log" >&2; echo "run.sh: error: configuring trac0r failed" >&2; exit 1; }
cmake --build "$T0" --target trac0r_viewer -j"$(nproc)" > "$T0/build.log" 2>&1 ||
  { tail -30 "$T0/build.log" >&2; echo "run.sh: error: building trac0r failed" >&2; exit 1; }

WORK=$(mktemp -d)
XPID=
cleanup() { [ -n "$XPID" ] && kill "$XPID" 2> /dev/null; rm -rf "$WORK"; }
trap cleanup EXIT
# A display of our own: the first free number from 90.
for d in $(seq 90 140); do
  [ -e "/tmp/.X$d-lock" ] && continue
  Xvfb ":$d" -screen 0 1024x768x24 -nolisten tcp > "$WORK/xvfb.log" 2>&1 &
  XPID=$!
  sleep 1
  if kill -0 "$XPID" 2> /dev/null; then DISPLAY_NUM=":$d"; break; fi
  XPID=
done
[ -n "$XPID" ] || { echo "run.sh: error: could not start Xvfb" >&2; exit 1; }

mkdir -p "$OUT"
LOG=$OUT/log.txt
load1() { cut -d' ' -f1 /proc/loadavg; }
{
  echo "== date: $(date -u +%FT%TZ)  commit: $(git -C "$ROOT" rev-parse --short HEAD)  host: $(hostname)"
  echo "== cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores"
  echo "== trac0r: $TRAC0R_DIR at $(git -C "$TRAC0R_DIR" rev-parse --short HEAD 2>/dev/null || echo 'unknown commit'); submodules:"
  git -C "$TRAC0R_DIR" submodule status 2>/dev/null | sed 's/^/==   /' || true
  echo "== trac0r frames: -f$F1 and -f$F2; clpath: $SPP spp; $ROUNDS rounds"
  echo "== uptime before: $(uptime)"
} | tee "$LOG"
DATE_START=$(date -u '+%Y-%m-%d %H:%M UTC')
echo "round,order,load1,renderer,msamples_per_s,seconds,samples" > "$OUT/runs.csv"

trac0r_seconds() {  # frames flag -> wall seconds of the whole process
  local s e
  s=$(date +%s.%N)
  (cd "$WORK" && DISPLAY=$DISPLAY_NUM "$T0/trac0r_viewer" "-f$1" > "$WORK/t0.txt" 2>&1) ||
    { cat "$WORK/t0.txt" >&2; echo "run.sh: error: trac0r_viewer -f$1 failed" >&2; exit 1; }
  e=$(date +%s.%N)
  cat "$WORK/t0.txt" >> "$LOG"
  python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.4f}')" "$s" "$e"
}

run_trac0r() {  # round, order
  local l a b
  l=$(load1)
  # trac0r reads its fonts from res/ beside where it runs.
  ln -sfn "$TRAC0R_DIR/res" "$WORK/res"
  echo "== round $1: trac0r OpenMP (load $l)" | tee -a "$LOG"
  a=$(trac0r_seconds "$F1")
  b=$(trac0r_seconds "$F2")
  echo "   -f$F1: $a s, -f$F2: $b s" | tee -a "$LOG"
  python3 -c "import sys; a, b, n = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]) * 800 * 640
print(f'$1,$2,$l,trac0r_openmp,{n / (b - a) * 1e-6:.4f},{b - a:.4f},{n}')" "$a" "$b" "$((F2 - F1))" >> "$OUT/runs.csv"
}

run_clpath() {  # round, order, name, options...
  local r=$1 o=$2 name=$3 l
  shift 3
  l=$(load1)
  echo "== round $r: clpath render, $name (load $l)" | tee -a "$LOG"
  "$CLPATH" render "$SCENE" --width 800 --height 640 --spp "$SPP" "$@" -q -o "$WORK/$name.exr" "${DEV[@]}" \
    > "$WORK/c.txt" 2>&1 || { cat "$WORK/c.txt" >&2; echo "run.sh: error: clpath render failed" >&2; exit 1; }
  grep '^summary:' "$WORK/c.txt" | tee -a "$LOG"
  python3 - "$WORK/c.txt" "$r" "$o" "$l" "$name" >> "$OUT/runs.csv" <<'PY'
import re, sys
line = [x for x in open(sys.argv[1]) if x.startswith("summary:")][-1]
f = dict(re.findall(r"(\w+)=(\"[^\"]*\"|\S+)", line))
s, ms = float(f["render_s"]), float(f["msamples_per_s"])
print(f"{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{sys.argv[5]},{ms:.4f},{s:.4f},{ms * s * 1e6:.0f}")
PY
}

# PoCL compiles a kernel for its work-group and grid sizes at its first launch, inside
# the render's time, and keeps it in its cache: one small render of each
# configuration at full size first, untimed, so that every timed render finds it there
# (trac0r is compiled ahead of time).
echo "== warm-up: PoCL's kernel cache" | tee -a "$LOG"
"$CLPATH" render "$SCENE" --width 800 --height 640 --spp 1 -q -o "$WORK/warm.exr" "${DEV[@]}" >> "$LOG" 2>&1
"$CLPATH" render "$SCENE" --width 800 --height 640 --spp 1 --integrator path-bsdf --rr depth --max-depth 10 -q \
  -o "$WORK/warm.exr" "${DEV[@]}" >> "$LOG" 2>&1

steps=(trac0r default estimator)
for round in $(seq 1 "$ROUNDS"); do
  for k in 0 1 2; do
    case ${steps[$(( (k + round - 1) % 3 ))]} in
      trac0r) run_trac0r "$round" "$k" ;;
      default) run_clpath "$round" "$k" clpath_default ;;
      estimator) run_clpath "$round" "$k" clpath_trac0r_estimator --integrator path-bsdf --rr depth --max-depth 10 ;;
    esac
  done
done
echo "== uptime after: $(uptime)" | tee -a "$LOG"

python3 - "$OUT" "$DATE_START" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$(git -C "$ROOT" rev-parse --short HEAD)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores" \
  "$("$CLPATH" devices 2>/dev/null | grep -m1 '\[' | sed 's/^ *//')" \
  "$(git -C "$TRAC0R_DIR" rev-parse --short HEAD 2>/dev/null || echo unknown)" "$F1" "$F2" "$SPP" "${NOTE:-}" <<'PY'
import csv, statistics, sys
from collections import defaultdict
out, start, end, commit, cpu, device, t0commit, f1, f2, spp, note = sys.argv[1:]
runs = list(csv.DictReader(open(f"{out}/runs.csv")))
by = defaultdict(dict)
for r in runs:
    by[r["renderer"]][r["round"]] = r
rounds = sorted({r["round"] for r in runs}, key=int)
loads = [float(r["load1"]) for r in runs]
med = statistics.median
def ratio(a, b):
    xs = [float(by[a][k]["msamples_per_s"]) / float(by[b][k]["msamples_per_s"]) for k in rounds if k in by[a] and k in by[b]]
    return med(xs), min(xs), max(xs)
L = []
add = L.append
add("# Path tracing side by side with trac0r, on trac0r's scene")
add("")
add(f"- Device: clpath on OpenCL `{device}`; trac0r's OpenMP build on the same CPU, {cpu}, every core (OpenMP's default threads).")
add(f"- Date: {start} to {end}. clpath commit: {commit}. trac0r commit: {t0commit} (its submodules as it pins them, `log.txt`), "
    "built by its own CMake file (`-O3 -march=native -fopenmp`; `-Wno-error=range-loop-construct` so that GCC 12's new "
    "warning does not stop its `-Werror` build).")
add(f"- Load average (1 min) before each run: {min(loads):.2f} to {max(loads):.2f}." + (f" {note}" if note else ""))
add(f"- {len(rounds)} interleaved rounds (the order of the three runs rotates); each figure is the median of the rounds, "
    "each ratio the median of the rounds' ratios (range in brackets).")
add(f"- trac0r: its viewer's room (five walls, the lamp, two boxes, two spheres: 196 triangles, everything diffuse) at "
    f"800x640, one sample per pixel per frame; `trac0r_viewer -f{f1}` and `-f{f2}` timed whole under Xvfb, the "
    f"difference over the {int(f2) - int(f1)} extra frames. A frame includes its tone mapping and window update.")
add(f"- clpath: `clpath render scenes/cornell-thesis-diffuse.json --width 800 --height 640 --spp {spp}` (the same room, "
    "docs/thesis-scene.md), Msamples/s from its summary (samples over render_s: the render, after kernel builds); "
    "default settings (path tracing with next-event estimation and MIS, throughput roulette, at most 16 bounces), and with "
    "trac0r's estimator: `--integrator path-bsdf --rr depth --max-depth 10` (lights found only by BSDF sampling, "
    "roulette by depth, 10 bounces; docs/thesis-scene.md). Before the rounds, one untimed one-sample render of each "
    "at full size: PoCL compiles a kernel at its first launch, inside the render's time, and keeps it in its cache "
    "(a first render on a new machine pays that once; trac0r is compiled ahead of time).")
add("")
add("| renderer | Msamples/s | / trac0r OpenMP |")
add("|---|---:|---:|")
names = [("trac0r_openmp", "trac0r, OpenMP"), ("clpath_default", "clpath `render`, default settings"),
         ("clpath_trac0r_estimator", "clpath `render`, trac0r's estimator")]
for key, label in names:
    if key not in by:
        continue
    ms = med([float(r["msamples_per_s"]) for r in by[key].values()])
    r, lo, hi = ratio(key, "trac0r_openmp")
    add(f"| {label} | {ms:.3f} | **{r:.2f}** ({lo:.2f}–{hi:.2f}) |")
add("")
open(f"{out}/README.md", "w").write("\n".join(L) + "\n")
print("\n".join(L))
PY
echo "run.sh: wrote $OUT/{README.md,runs.csv,log.txt}"
