#!/usr/bin/env bash
# Adaptive sampling (render --noise-target) against uniform sampling at equal
# time, against the Mitsuba 3 references (benchmarks/references/mitsuba/,
# 4096 spp each, at their own size), on scenes whose noise is uneven.
# For each scene and noise target R:
#   - render --noise-target R --spp CAP (seed 7): its render_s, spp range and
#     relMSE (pbrt's, clpath compare), and its per-pixel sample-count image;
#   - equal samples: a uniform render of the adaptive one's mean spp (rounded
#     up), seed 7, and its relMSE: the gain of where the samples went, which
#     load on the machine cannot change;
#   - equal time: render --time render_s, uniform (seed 7): the spp it
#     reached and its relMSE, which adds adaptive sampling's own costs (the
#     pass boundaries) and is as noisy as the machine's load.
#   - the ratios uniform relMSE / adaptive relMSE (> 1: adaptive wins).
# MSE (not relative) of the adaptive and equal-samples images is kept too:
# relMSE weighs dark pixels most, the noise target bright noisy ones.
# The adaptive image is the same bits every round; the equal-time pair runs
# three times (adaptive first, then uniform, so that load falls on both alike).
# Writes results.csv, and per scene the adaptive image, its sample counts
# (PNG, grey: white the most; EXR: the counts) and the reference as PNG.
#
# Usage: benchmarks/adaptive/run.sh [CLPATH] [OUT]
#   (default build/clpath, benchmarks/results/pocl-epyc-2core/adaptive)
# CLPATH_ADAPTIVE_QUICK=1: one scene, one target, one round (for checking the script).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
clpath=${1:-$root/build/clpath}
out=${2:-$root/benchmarks/results/pocl-epyc-2core/adaptive}
refs=$root/benchmarks/references/mitsuba
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# name | scene file | what makes its noise uneven
scenes=(
  "cornell-thesis|scenes/cornell-thesis.json|smooth glass (caustics on the floor) and a rough conductor beside diffuse walls"
  "suzanne|scenes/suzanne/Suzanne.gltf|a bare mesh under the presentation's sky and sun: sky pixels converge at once"
  "glass-in-glass|scenes/hard/glass-in-glass.json|nested dielectrics under a constant environment"
)
targets=(0.1 0.05)
cap=1024
rounds=3
if [ "${CLPATH_ADAPTIVE_QUICK:-0}" = 1 ]; then
  scenes=("${scenes[@]:0:1}"); targets=(0.05); cap=256; rounds=1
fi

field() { sed -n "s/.*[ ]$1=\([^ ]*\).*/\1/p" | tail -1; }
relmse() { "$clpath" compare "$1" "$2" 2>/dev/null | field relmse; }
mse() { "$clpath" compare "$1" "$2" 2>/dev/null | field mse; }

echo "scene,noise_target,round,adaptive_render_s,adaptive_spp_min,adaptive_spp_max,adaptive_spp_mean,converged,adaptive_relmse,equal_samples_spp,equal_samples_relmse,equal_samples_ratio,equal_time_spp,equal_time_render_s,equal_time_relmse,equal_time_ratio,adaptive_mse,equal_samples_mse" > "$out/results.csv"
for entry in "${scenes[@]}"; do
  IFS='|' read -r name scene what <<< "$entry"
  ref=$refs/$name.exr
  read -r w h < <(oiiotool --info "$ref" | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1 \2/p')
  common=("$root/$scene" --width "$w" --height "$h" --seed 7 -q)
  "$clpath" render "${common[@]}" --spp 2 -o "$work/warm.exr" > /dev/null  # kernels compiled before any timed run
  for r in "${targets[@]}"; do
    for round in $(seq 1 "$rounds"); do
      a=$("$clpath" render "${common[@]}" --spp "$cap" --noise-target "$r" -o "$work/a.exr" -o "$work/a.png" \
            --sample-count-image "$work/n.exr" --sample-count-image "$work/n.png")
      t=$(echo "$a" | field render_s)
      e_a=$(relmse "$work/a.exr" "$ref"); m_a=$(mse "$work/a.exr" "$ref")
      mean=$(echo "$a" | field spp_mean)
      if [ "$round" = 1 ]; then
        n_eq=$(awk -v m="$mean" 'BEGIN{n=int(m); if (n<m) n++; print n}')
        "$clpath" render "${common[@]}" --spp "$n_eq" -o "$work/s.exr" > /dev/null
        e_s=$(relmse "$work/s.exr" "$ref"); m_s=$(mse "$work/s.exr" "$ref")
        ratio_s=$(awk -v u="$e_s" -v a="$e_a" 'BEGIN{printf "%.3f", u/a}')
      fi
      u=$("$clpath" render "${common[@]}" --time "$t" -o "$work/u.exr")
      e_u=$(relmse "$work/u.exr" "$ref")
      ratio=$(awk -v u="$e_u" -v a="$e_a" 'BEGIN{printf "%.3f", u/a}')
      echo "$name,$r,$round,$t,$(echo "$a" | field spp_min),$(echo "$a" | field spp_max),$mean,$(echo "$a" | field converged),$e_a,$n_eq,$e_s,$ratio_s,$(echo "$u" | field spp),$(echo "$u" | field render_s),$e_u,$ratio,$m_a,$m_s" >> "$out/results.csv"
      echo "$name R=$r round $round: adaptive ${t}s mean $mean spp relMSE $e_a; equal samples ($n_eq spp) relMSE $e_s (ratio $ratio_s); equal time $(echo "$u" | field spp) spp relMSE $e_u (ratio $ratio)" >&2
    done
    cp "$work/a.png" "$out/$name-R$r.png"
    cp "$work/n.png" "$out/$name-R$r.samples.png"
    cp "$work/n.exr" "$out/$name-R$r.samples.exr"
  done
  oiiotool "$ref" --colorconvert linear sRGB -d uint8 -o "$out/$name-mitsuba.png" 2>/dev/null || true
done
