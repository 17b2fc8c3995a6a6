#!/usr/bin/env bash
# One batch on a machine with an NVIDIA GPU, from a build folder copied there
# (the script builds nothing): registers the NVIDIA OpenCL driver, lists
# devices, runs every test program on the GPU, renders the default scene on
# the GPU and on the machine's CPU through PoCL, times a longer GPU render,
# path tracing against Embree (bench path) and the scaling and ray benchmarks.
# Logs and images go to $OUT.
# Usage: benchmarks/gpu/run_gpu_checks.sh BUILD_DIR
#   (a -DCLPATH_WITH_OIIO=OFF -DCLPATH_WITH_VIEWER=OFF -DCLPATH_WITH_EMBREE=OFF build: bench rays then
#   prints each kernel's private memory and preferred work-group multiple, without the Embree baseline)
set -u
B=${1:-build-gpu}
OUT=${OUT:-/tmp/clpath-gpu-out}
mkdir -p "$OUT" /etc/OpenCL/vendors
echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
export CLPATH_CACHE_DIR=/tmp/clpath-cache
{
  echo "== date: $(date -u +%FT%TZ)  host: $(hostname)"
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null
  "$B/clpath" devices
} 2>&1 | tee "$OUT/devices.txt"

echo "== tests on the GPU" | tee "$OUT/gpu-tests.txt"
for t in "$B"/tests/*_test; do
  echo "-- $(basename "$t")"
  CLPATH_DEVICE=nvidia timeout 300 "$t" --gtest_brief=1 2>&1 | tail -n 4
done 2>&1 | tee -a "$OUT/gpu-tests.txt"

# Equality in distribution between the GPU and PoCL (bit equality cannot hold
# between devices: their float arithmetic and builtins differ), and the
# hard-case suite on the GPU.
echo "== cross-device agreement and robustness suite on the GPU" | tee "$OUT/robustness.txt"
CLPATH_DEVICE=portable CLPATH_DEVICE_B=nvidia timeout 600 ctest --test-dir "$B" -R "ReferenceAgreement.CrossDevice" \
  --output-on-failure 2>&1 | tail -n 30 | tee -a "$OUT/robustness.txt"
CLPATH_DEVICE=nvidia timeout 900 ctest --test-dir "$B" -j4 --output-on-failure \
  -R "Watertight|RayEdgeCases|Scale\.|Accumulation|LightTransportHard|DegenerateGeometry|BvhExtremes|RngSpectrum|HardScenes|ReferenceAgreement" \
  2>&1 | tail -n 30 | tee -a "$OUT/robustness.txt"

echo "== renders" | tee "$OUT/summary.txt"
# Same scene and settings on both devices, independent seeds, for the statistical comparison.
"$B/clpath" render --device nvidia --spp 256 --seed 1 -q -o "$OUT/cornell-gpu-256.pfm" 2>&1 | tee -a "$OUT/summary.txt"
"$B/clpath" render --device portable --spp 256 --seed 2 -q -o "$OUT/cornell-pocl-256.pfm" 2>&1 | tee -a "$OUT/summary.txt"
# Speed: steady state on the GPU.
"$B/clpath" render --device nvidia --spp 4096 --seed 3 -q -o "$OUT/cornell-gpu-4096.pfm" 2>&1 | tee -a "$OUT/summary.txt"
"$B/clpath" render --device nvidia --spp 1024 --seed 4 --rr depth --max-depth 10 -q -o /tmp/thesis-rule.pfm 2>&1 | tee -a "$OUT/summary.txt"

# Path tracing on the GPU against the Embree path tracer on the machine's CPU
# cores (same estimator; the two images are checked to agree). Needs a build
# with Embree; a build without it says so and the batch goes on.
echo "== bench path: GPU against Embree on the CPU" | tee "$OUT/bench-path.txt"
for s in scenes/cornell-point.json scenes/cornell-classic.json scenes/bunny.json; do
  timeout 600 "$B/clpath" bench path "$s" --device nvidia --width 512 --height 512 --spp 64 --max-depth 4 \
    --rounds 3 2>&1 | tail -n 12 | tee -a "$OUT/bench-path.txt"
done

# The full scaling and ray-batch benchmarks on the GPU, results under
# $OUT/results/<device-dir>/{scaling,rays}: copy them into
# benchmarks/results/ and plot them where matplotlib is installed
# (benchmarks/scaling/plot_scaling.py).
# GPU_BENCH_DIR names the device folder (default nvidia-h100); the rays runs
# include the scene sizes of tinybvh's published traversal figures (bunny,
# room:1003542, room:3996202).
echo "== scaling and ray-batch benchmarks on the GPU" | tee "$OUT/bench.txt"
GPU_DIR=${GPU_BENCH_DIR:-nvidia-h100}
PLOT=0 SCALING_MAX=${SCALING_MAX:-3e7} TIME_CAP=${TIME_CAP:-60} RAY_LAUNCHES=${RAY_LAUNCHES:-10} \
  timeout 1500 benchmarks/scaling/run.sh "$GPU_DIR" nvidia "$B" 2>&1 | tail -n 60 | tee -a "$OUT/bench.txt"
mkdir -p "$OUT/results" && cp -r "benchmarks/results/$GPU_DIR" "$OUT/results/" 2>/dev/null
