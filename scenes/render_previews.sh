#!/bin/sh
# Renders a small picture of every bundled scene (and one generated scaling
# scene) into docs/images/<scene>.png, for the README and docs/scene-format.md.
#
#   scenes/render_previews.sh [CLPATH]     (default: build/clpath)
#
# WIDTH (default 320) and SPP (default 128) may be set in the environment; the
# height follows each scene's own aspect ratio.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
clpath=${1:-$root/build/clpath}
width=${WIDTH:-320}
spp=${SPP:-128}
out=$root/docs/images
if [ ! -x "$clpath" ]; then
    echo "render_previews.sh: $clpath is not an executable clpath (build it, or name one)" >&2
    exit 1
fi
mkdir -p "$out"

# The height that keeps a scene's aspect ratio at $width pixels wide.
height_for() {
    python3 -c 'import json, sys
w, h = json.load(open(sys.argv[1]))["camera"].get("resolution", [640, 480])
print(max(1, round(int(sys.argv[2]) * h / w)))' "$1" "$width"
}

for scene in "$root"/scenes/*.json; do
    name=$(basename "$scene" .json)
    echo "render_previews.sh: $name"
    "$clpath" render "$scene" --width "$width" --height "$(height_for "$scene")" --spp "$spp" -q -o "$out/$name.png"
done
# The scaling scene, at 100,000 triangles; it has the thesis camera (800 x 640).
echo "render_previews.sh: scaling:100000"
"$clpath" render scaling:100000 --width "$width" --height $((width * 640 / 800)) --spp "$spp" -q -o "$out/scaling.png"
# Textured scenes: the Suzanne glTF model on its own, and the textured OBJ/MTL scene.
echo "render_previews.sh: suzanne"
"$clpath" render "$root/scenes/suzanne/Suzanne.gltf" --width "$width" --height $((width * 3 / 4)) --spp "$spp" -q -o "$out/suzanne.png"
echo "render_previews.sh: textured"
"$clpath" render "$root/scenes/textured/textured.json" --width "$width" --height $((width * 3 / 4)) --spp "$spp" -q -o "$out/textured.png"
echo "render_previews.sh: pictures in $out"
