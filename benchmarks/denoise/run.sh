#!/usr/bin/env bash
# Denoised against raw at equal time, against the Mitsuba 3 references
# (benchmarks/references/mitsuba/, 4096 spp each, at their own size).
# For each scene:
#   - a raw ladder (1..1024 spp, seed 7): render_s and relMSE (pbrt's, clpath compare);
#   - render --denoise at a few low spp: the estimate's and the denoised image's
#     relMSE, with the time of the render, the guides' passes and the denoiser;
#   - a raw render given the denoised run's whole time (--time): equal time;
#   - what the denoised image is worth: the raw spp of equal relMSE,
#     interpolated log-log in the ladder (">1024" past its end).
# Then the denoiser's own time per megapixel at 512x512 and 1024x1024.
# Writes results.csv, ladder.csv, denoiser_time.csv and PNGs (4 spp raw and
# denoised, the reference) to OUT.
#
# Usage: benchmarks/denoise/run.sh [CLPATH] [OUT]
#   (default build/clpath, benchmarks/results/pocl-epyc-2core/denoise)
# CLPATH_DENOISE_QUICK=1: two scenes, a short ladder (for checking the script).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
clpath=${1:-$root/build/clpath}
out=${2:-$root/benchmarks/results/pocl-epyc-2core/denoise}
refs=$root/benchmarks/references/mitsuba
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# name | scene file | what it shows
scenes=(
  "cornell-classic|scenes/cornell-classic.json|diffuse room, area light"
  "gltf-textured|benchmarks/references/scenes/gltf-textured.json|glTF material, sRGB base colour textures"
  "cornell-thesis|scenes/cornell-thesis.json|smooth tinted glass and a rough conductor in a room"
)
ladder=(1 2 4 8 16 32 64 128 256 512 1024)
denoise_spp=(1 4 16 64)
if [ "${CLPATH_DENOISE_QUICK:-0}" = 1 ]; then
  scenes=("${scenes[@]:0:2}"); ladder=(1 4 16); denoise_spp=(4)
fi

field() { sed -n "s/.*[ ]$1=\([^ ]*\).*/\1/p" | tail -1; }
relmse() { "$clpath" compare "$1" "$2" 2>/dev/null | field relmse; }

echo "scene,spp,render_s,guides_s,denoise_s,total_s,relmse_raw,relmse_denoised,equal_time_raw_spp,equal_time_raw_relmse,denoised_worth_raw_spp" > "$out/results.csv"
echo "scene,spp,render_s,relmse" > "$out/ladder.csv"
for entry in "${scenes[@]}"; do
  IFS='|' read -r name scene what <<< "$entry"
  ref=$refs/$name.exr
  read -r w h < <(oiiotool --info "$ref" | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1 \2/p')
  common=("$root/$scene" --width "$w" --height "$h" --seed 7 -q)
  # Warm-up: the kernels (path and the two views) compile once and load from
  # the cache after; no timed run pays for a compile.
  "$clpath" render "${common[@]}" --spp 1 --denoise -o "$work/warm.exr" > /dev/null
  for n in "${ladder[@]}"; do
    s=$("$clpath" render "${common[@]}" --spp "$n" -o "$work/raw.exr" | field render_s)
    echo "$name,$n,$s,$(relmse "$work/raw.exr" "$ref")" >> "$out/ladder.csv"
  done
  for n in "${denoise_spp[@]}"; do
    line=$("$clpath" render "${common[@]}" --spp "$n" --denoise -o "$work/d.exr" -o "$work/d.png")
    r=$(echo "$line" | field render_s); g=$(echo "$line" | field guides_s); d=$(echo "$line" | field denoise_s)
    total=$(awk -v a="$r" -v b="$g" -v c="$d" 'BEGIN{printf "%.3f", a+b+c}')
    e_raw=$(relmse "$work/d.exr" "$ref"); e_den=$(relmse "$work/d.denoised.exr" "$ref")
    eq=$("$clpath" render "${common[@]}" --time "$total" -o "$work/eq.exr")
    eq_spp=$(echo "$eq" | field spp); e_eq=$(relmse "$work/eq.exr" "$ref")
    # The raw spp whose relMSE equals the denoised image's, log-log between ladder rungs.
    worth=$(awk -F, -v s="$name" -v e="$e_den" '$1==s{n[++k]=$2; r[k]=$4}
      END{for(i=1;i<=k;i++) if(r[i]<=e){ if(i==1){printf "<=%d", n[1]; exit}
            t=(log(e)-log(r[i-1]))/(log(r[i])-log(r[i-1])); printf "%.0f", exp(log(n[i-1])+t*(log(n[i])-log(n[i-1]))); exit}
          printf ">%d", n[k]}' "$out/ladder.csv")
    echo "$name,$n,$r,$g,$d,$total,$e_raw,$e_den,$eq_spp,$e_eq,$worth" >> "$out/results.csv"
    if [ "$n" = 4 ]; then
      cp "$work/d.png" "$out/$name-4spp.png"; cp "$work/d.denoised.png" "$out/$name-4spp.denoised.png"
    fi
    echo "$name $n spp: raw $e_raw, denoised $e_den (worth $worth raw spp); equal time ${total}s raw $eq_spp spp $e_eq" >&2
  done
  oiiotool "$ref" --colorconvert linear sRGB -d uint8 -o "$out/$name-mitsuba.png" 2>/dev/null || true
done

# The denoiser's own time per megapixel (the filter alone, guides not included).
# The guides' two passes (64 spp each, scene preparation included) and one
# raw spp at the same size, to scale the comparison to larger images.
echo "width,height,denoise_s,s_per_megapixel,guides_s,render_s_1spp" > "$out/denoiser_time.csv"
sizes=("512 512" "1024 1024"); [ "${CLPATH_DENOISE_QUICK:-0}" = 1 ] && sizes=("256 256")
for size in "${sizes[@]}"; do
  read -r w h <<< "$size"
  for i in 1 2 3; do
    line=$("$clpath" render "$root/scenes/cornell-classic.json" --width "$w" --height "$h" --spp 1 --denoise -q \
        -o "$work/t.exr")
    d=$(echo "$line" | field denoise_s)
    echo "$w,$h,$d,$(awk -v d="$d" -v w="$w" -v h="$h" 'BEGIN{printf "%.3f", d/(w*h*1e-6)}'),$(echo "$line" | field guides_s),$(echo "$line" | field render_s)" >> "$out/denoiser_time.csv"
  done
done
echo "wrote $out" >&2
