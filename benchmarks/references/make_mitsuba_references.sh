#!/usr/bin/env bash
# The primary references: Mitsuba 3 renders of every bundled scene and of the
# reference scenes in benchmarks/references/scenes/ (the light and material
# kinds the bundled scenes lack), into benchmarks/references/mitsuba/:
# NAME.exr (the mean of SEEDS renders of SPP samples each) and NAME.var.exr
# (one sample's variance, from the seeds' spread; see mitsuba_reference.py).
#
# Usage: benchmarks/references/make_mitsuba_references.sh [BUILD_DIR] [SPP] [SEEDS] [NAME...]
# (default 256 spp x 16 seeds; NAME: only those scenes). Creates the Python
# environment with benchmarks/references/venv.sh on first use. CI does not
# need Mitsuba: the references are committed.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$root/build}; SPP=${2:-256}; SEEDS=${3:-16}; shift $(( $# < 3 ? $# : 3 ))
here=$root/benchmarks/references
clpath=$B/clpath
[ -x "$clpath" ] || { echo "make_mitsuba_references.sh: no $clpath: build clpath first" >&2; exit 1; }
python=$("$here/venv.sh" "$B/.venv-mitsuba")
mkdir -p "$here/mitsuba"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# name  scene  width  height (even: the tests also compare at half size)
scenes=(
  "cornell-classic        scenes/cornell-classic.json                      64 64"
  "cornell-thesis         scenes/cornell-thesis.json                       64 52"
  "cornell-thesis-diffuse scenes/cornell-thesis-diffuse.json               64 52"
  "bunny                  scenes/bunny.json                                64 52"
  "bunny-instances        scenes/bunny-instances.json                      64 52"
  "far-from-origin        scenes/hard/far-from-origin.json                 64 64"
  "glass-in-glass         scenes/hard/glass-in-glass.json                  64 48"
  "tiny-light             scenes/hard/tiny-light.json                      64 48"
  "punctual-lights        benchmarks/references/scenes/punctual-lights.json 64 48"
  "metals                 benchmarks/references/scenes/metals.json         64 48"
  "rough-glass-sky        benchmarks/references/scenes/rough-glass-sky.json 64 48"
  "thin-lens              benchmarks/references/scenes/thin-lens.json      64 48"
  "gltf-textured          benchmarks/references/scenes/gltf-textured.json  64 48"
  "gltf-metals            benchmarks/references/scenes/gltf-metals.json    64 48"
  "gltf-cutout            benchmarks/references/scenes/gltf-cutout.json    64 48"
  "gltf-normal-map        benchmarks/references/scenes/gltf-normal-map.json 64 48"
  "gltf-clearcoat         benchmarks/references/scenes/gltf-clearcoat.json 64 48"
  "gltf-transmission      benchmarks/references/scenes/gltf-transmission.json 64 48"
  "gltf-instances         benchmarks/references/scenes/gltf-instances.json 64 48"
  "suzanne                scenes/suzanne/Suzanne.gltf                      64 48"
  "textured               scenes/textured/textured.json                    64 48"
  "room-lamp-sky          scenes/room-lamp-sky.json                        64 48"
  "city                   city:2000                                        64 48"
)
for s in "${scenes[@]}"; do
  read -r name scene w h <<<"$s"
  if [ $# -gt 0 ] && ! printf '%s\n' "$@" | grep -qx "$name"; then continue; fi
  src=$scene; [[ $scene == *:* ]] || src=$root/$scene  # a built-in scene (city:N) by name
  "$clpath" export "$src" "$work/$name.json" --format mitsuba --width "$w" --height "$h" > /dev/null
  nice -n 19 "$python" "$here/mitsuba_reference.py" "$work/$name.json" "$work/$name.exr" --spp "$SPP" --seeds "$SEEDS" \
    2> >(grep -v ': seed ' >&2) | tee -a "$work/log.txt"
  mv "$work/$name.exr" "$work/$name.var.exr" "$here/mitsuba/"
done
