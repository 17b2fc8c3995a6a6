#!/usr/bin/env bash
# Every reference image. First the primary ones, Mitsuba 3 renders of every
# bundled scene and reference scene (make_mitsuba_references.sh; skip with
# NO_MITSUBA=1), then the older ones (skip with NO_CYCLES=1):
#  - cornell-classic-cycles.exr: Blender Cycles, an independent renderer, from
#    `clpath export` (diffuse and emissive surfaces only), 128x128;
#  - cornell-thesis-diffuse-cycles.exr: the same for the thesis room with
#    every surface diffuse (its lamp is two-sided), 160x128;
#  - cornell-thesis-clpath.exr: cornell-thesis has glass and glossy surfaces,
#    which Cycles models differently, so its reference is a high-sample clpath
#    render (path: NEE + MIS, throughput roulette, seed 1000, which no
#    benchmark run uses), 160x128. It is clpath's own estimate, not an
#    independent one; it is said so wherever it is used.
# Then compares clpath with Cycles on the first two (clpath compare) into
# references/agreement.txt.
#
# Usage: benchmarks/references/make_references.sh [BUILD_DIR] [CYCLES_SPP] [CLPATH_SPP]
# (CLPATH_CHECK_SPP=N: the clpath renders of the agreement check, default 1024)
# Blender (Debian's `blender`, 3.4) is installed with apt when missing; CI
# does not need it: the small references are committed.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$root/build}; CYCLES_SPP=${2:-4096}; CLPATH_SPP=${3:-4096}
here=$root/benchmarks/references
clpath=$B/clpath
[ -x "$clpath" ] || { echo "make_references.sh: no $clpath: build clpath first" >&2; exit 1; }
[ -n "${NO_MITSUBA:-}" ] || "$here/make_mitsuba_references.sh" "$B"
[ -z "${NO_CYCLES:-}" ] || exit 0
if ! command -v blender >/dev/null; then
  echo "make_references.sh: installing Blender (apt-get install blender)" >&2
  sudo=(); [ "$(id -u)" = 0 ] || sudo=(sudo)
  "${sudo[@]}" apt-get install -y --no-install-recommends blender
fi
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

cycles() {  # scene width height
  local name; name=$(basename "$1" .json)
  "$clpath" export "$1" "$work/$name.json" --width "$2" --height "$3"
  (cd "$work" && blender -b --factory-startup -P "$here/cycles_reference.py" -- \
     "$name.json" "$work/$name-cycles.exr" --samples "$CYCLES_SPP" --seed 1 | grep -v '^Fra:')
  mv "$work/$name-cycles.exr" "$here/$name-cycles.exr"
}
cycles "$root/scenes/cornell-classic.json" 128 128
cycles "$root/scenes/cornell-thesis-diffuse.json" 160 128
"$clpath" render "$root/scenes/cornell-thesis.json" --width 160 --height 128 --spp "$CLPATH_SPP" --seed 1000 -q \
  -o "$work/cornell-thesis-clpath.exr"
mv "$work/cornell-thesis-clpath.exr" "$here/cornell-thesis-clpath.exr"

# clpath against Cycles. Two clpath renders with different seeds give the
# noise alone: with per-sample variances s2 (clpath) and c2 (Cycles), the
# clpath-clpath MSE is 2 s2/N and the clpath-Cycles one s2/N + c2/CYCLES_SPP +
# bias^2, so agreement means the second is about (1/2 + N c2 / (2 s2 CYCLES_SPP))
# times the first, and no channel mean differs by much more than its noise.
N=${CLPATH_CHECK_SPP:-1024}
{
  echo "date: $(date -u +%FT%TZ)  commit: $(git -C "$root" rev-parse --short HEAD)  blender: $(blender --version | head -1)"
  "$clpath" devices | sed -n 2p | sed 's/^ *//'
  for s in cornell-classic:128:128 cornell-thesis-diffuse:160:128; do
    IFS=: read -r name w h <<<"$s"
    for seed in 2000 3000; do
      "$clpath" render "$root/scenes/$name.json" --width "$w" --height "$h" --spp "$N" --seed "$seed" -q \
        -o "$work/$name-clpath-$seed.exr" > /dev/null
    done
    for mask in "" "--mask-above 0.8 --mask-grow 1"; do
      echo "== $name ${mask:+(lamp left out: $mask)}"
      echo -n "clpath $N spp vs clpath $N spp, other seed: "
      "$clpath" compare "$work/$name-clpath-2000.exr" "$work/$name-clpath-3000.exr" $mask
      echo -n "clpath $N spp vs Cycles $CYCLES_SPP spp:         "
      "$clpath" compare "$work/$name-clpath-2000.exr" "$here/$name-cycles.exr" $mask
    done
  done
} | tee "$here/agreement.txt"
