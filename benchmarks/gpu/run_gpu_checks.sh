#!/usr/bin/env bash
# The GPU check: one batch, under 8 minutes by its own timeouts, on a machine
# with an NVIDIA GPU and a prebuilt bundle (benchmarks/gpu/build_gpu_bundle.sh
# writes it to .gpu/: clpath, the cross-device test, the shared libraries the
# GPU machine lacks). It builds nothing. In order:
#   1. devices: the NVIDIA driver registered with the ICD loader, every device;
#   2. correctness: the default scene on the GPU in both kernel shapes (their
#      bits compared) and on the machine's CPU through PoCL; the cross-device
#      test (equality in distribution, per pixel, GPU against PoCL, both
#      shapes); bench rays checks every batch's hits against the CPU walk;
#   3. speed: bench rays on bunny and room:1003542 (Mrays/s, primary / shadow /
#      diffuse), and Msamples/s of the megakernel against the wavefront on three
#      scenes (all diffuse; the bunny; glass, whose textures-free materials need
#      no image library), three runs each (the median goes in the table).
# Logs, images and summary.txt (the table) go to $OUT.
# Usage: benchmarks/gpu/run_gpu_checks.sh [BUNDLE_DIR]   (from the repository root)
set -u
B=${1:-.gpu}
OUT=${OUT:-/tmp/clpath-gpu-out}
mkdir -p "$OUT" /etc/OpenCL/vendors
[ -e /usr/lib/libnvidia-opencl.so.1 ] && echo /usr/lib/libnvidia-opencl.so.1 >/etc/OpenCL/vendors/nvidia.icd
export LD_LIBRARY_PATH="$B/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export CLPATH_CACHE_DIR=/tmp/clpath-gpu-cache
CLP="$B/clpath"
BUNNY=$B/scenes/bunny.json  # the bundle's copy, reading the mesh beside it
GPU=${GPU_DEVICE:-nvidia}  # the device to check, by name (a dry run elsewhere: GPU_DEVICE=portable)
T0=$(date +%s)
LIMITS=0

# step NAME SECONDS COMMAND...: runs COMMAND under a timeout, its output to
# $OUT/NAME.log and the terminal, and notes its time and exit status.
step() {
  local name=$1 limit=$2 t rc
  shift 2
  LIMITS=$((LIMITS + limit))
  echo "== $name (limit ${limit} s)"
  t=$(date +%s%N)
  timeout "$limit" "$@" >"$OUT/$name.log" 2>&1
  rc=$?
  tail -n 25 "$OUT/$name.log"
  printf '%-28s rc=%-3s %6.1f s\n' "$name" "$rc" "$(( ($(date +%s%N) - t) / 1000000 ))e-3" >>"$OUT/steps.txt"
}

step devices 20 bash -c "date -u +%FT%TZ; nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader; \
  \"$CLP\" devices"

# Correctness. The same seed in both shapes: on one device they should agree
# bit for bit wherever the compiler emits the same arithmetic for both.
R="$CLP render --spp 256 -q"
step render-gpu-mega 30 $R --device $GPU --kernel mega --seed 1 -o "$OUT/cornell-gpu-mega.pfm"
step render-gpu-wavefront 30 $R --device $GPU --kernel wavefront --seed 1 -o "$OUT/cornell-gpu-wavefront.pfm"
step render-pocl 45 $CLP render --spp 64 -q --device portable --seed 2 -o "$OUT/cornell-pocl.pfm"
step compare-shapes 10 bash -c "cmp \"$OUT/cornell-gpu-mega.pfm\" \"$OUT/cornell-gpu-wavefront.pfm\" && echo 'same bits'; \
  \"$CLP\" compare \"$OUT/cornell-gpu-wavefront.pfm\" \"$OUT/cornell-gpu-mega.pfm\"; \
  \"$CLP\" compare \"$OUT/cornell-pocl.pfm\" \"$OUT/cornell-gpu-mega.pfm\""
step cross-device 60 env CLPATH_DEVICE=portable CLPATH_DEVICE_B=$GPU \
  "$B/tests/reference_agreement_test" --gtest_filter=ReferenceAgreement.CrossDevice

# Traversal: the ray batches, each checked against the CPU walk.
step rays-bunny 40 $CLP bench rays "$BUNNY" --device $GPU --launches 10 --no-embree --csv "$OUT/rays-bunny.csv"
step rays-room-1M 50 $CLP bench rays room:1003542 --device $GPU --launches 10 --no-embree --csv "$OUT/rays-room.csv"

# Path tracing: megakernel against wavefront, three runs each, alternating.
speed() {
  for scene in "" "$BUNNY" scenes/hard/glass-in-glass.json; do
    for run in 1 2 3; do
      for shape in mega wavefront; do
        echo "scene=${scene:-default} shape=$shape run=$run $($CLP render $scene --device $GPU --kernel $shape \
          --spp 1024 -q -o /tmp/speed.pfm 2>&1 | grep -o 'msamples_per_s=[0-9.]*\|mrays_per_s=[0-9.]*' | tr '\n' ' ')"
      done
    done
  done
}
export -f speed
export CLP GPU BUNNY
step speed 180 bash -c speed

{
  echo "clpath GPU check, $(date -u +%F), commit $(cat "$B/COMMIT" 2>/dev/null)"
  grep -v '^20' "$OUT/devices.log" | head -n 1
  echo "limits sum: ${LIMITS} s; took $(( $(date +%s) - T0 )) s"
  echo
  cat "$OUT/steps.txt"
  echo
  echo "Mrays/s on the GPU (primary / shadow / diffuse), hits checked against the CPU walk:"
  grep -h '^primary\|^shadow\|^diffuse' "$OUT/rays-bunny.log" | sed 's/^/  bunny /'
  grep -h '^primary\|^shadow\|^diffuse' "$OUT/rays-room-1M.log" | sed 's/^/  room:1003542 /'
  echo
  echo "Msamples/s, median of 3 (1024 spp):"
  python3 - "$OUT/speed.log" <<'PY'
import re, sys, statistics
runs = {}
for line in open(sys.argv[1]):
    m = re.match(r"scene=(\S+) shape=(\S+) run=\d+ msamples_per_s=([\d.]+)", line)
    if m: runs.setdefault((m[1], m[2]), []).append(float(m[3]))
for (scene, shape), v in sorted(runs.items()):
    print(f"  {scene:30s} {shape:10s} {statistics.median(v):9.2f}   runs {v}")
PY
  echo
  grep -h 'same bits\|differ\|rmse\|RMSE' "$OUT/compare-shapes.log" | head -n 6
  grep -h '\[ devices \]\|PASSED\|FAILED' "$OUT/cross-device.log"
} | tee "$OUT/summary.txt"
