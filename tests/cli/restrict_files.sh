#!/usr/bin/env bash
# --restrict-files DIR (and CLPATH_RESTRICT_FILES) refuses every file outside
# DIR, whichever way a scene reaches it: "..", a %2F-encoded uri, a symbolic
# link, an absolute path, a .glb's buffer uri. Each canary file outside the
# folder holds text, not an image or buffer: without the restriction
# (the control) it is opened and refused for its contents, which shows the
# path does reach it; with it, the message names the resolved path.
#   restrict_files.sh CLPATH OUT_DIR
set -euo pipefail
clpath=$1
out=$2
rm -rf "$out"
mkdir -p "$out/jail/sub" "$out/outside"
echo "canary" >"$out/outside/canary.png"
echo "Ns canary" >"$out/outside/canary.mtl"
echo "canary" >"$out/outside/canary.bin"
ln -s ../outside/canary.png "$out/jail/link.png"
small=(--spp 1 --width 8 --height 8 -q)

python3 - "$out" <<'PY'
import base64, json, struct, sys
out = sys.argv[1]
pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
def doc(image_uri=None, buffer_uri=None):
    d = {"asset": {"version": "2.0"},
         "buffers": [{"byteLength": len(pos), "uri": buffer_uri or
                      "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}],
         "bufferViews": [{"buffer": 0, "byteLength": len(pos)}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
         "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}
    if image_uri:
        d["images"] = [{"uri": image_uri}]
        d["textures"] = [{"source": 0}]
        d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        d["meshes"][0]["primitives"][0]["material"] = 0
    return d
json.dump(doc(image_uri="..%2Foutside%2Fcanary.png"), open(f"{out}/jail/percent.gltf", "w"))
json.dump(doc(image_uri="link.png"), open(f"{out}/jail/symlink.gltf", "w"))
json.dump(doc(image_uri=f"{out}/outside/canary.png".replace("/", "%2F")), open(f"{out}/jail/absolute.gltf", "w"))
j = json.dumps(doc(buffer_uri="../outside/canary.bin")).encode()
j += b" " * (-len(j) % 4)
open(f"{out}/jail/buffer.glb", "wb").write(b"glTF" + struct.pack("<III", 2, 20 + len(j), len(j)) + b"JSON" + j)
tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
open(f"{out}/jail/sub/dotdot.obj", "w").write("mtllib ../../outside/canary.mtl\n" + tri)
open(f"{out}/jail/absolute.obj", "w").write(f"mtllib {out}/outside/canary.mtl\n" + tri)
PY

# refused SCENE WHAT: with the restriction, exit 1 and the resolved path named.
refused() {
    local scene=$1 what=$2 rc=0
    "$clpath" render "$scene" "${small[@]}" --restrict-files "$out/jail" -o "$out/r.pfm" >"$out/log" 2>&1 || rc=$?
    cat "$out/log"
    [ $rc -eq 1 ] || { echo "$scene: exit $rc, not 1"; exit 1; }
    grep -q "resolves to $out/outside/$what, outside $out/jail, the folder --restrict-files allows" "$out/log" ||
        { echo "$scene: the refusal does not name $out/outside/$what"; exit 1; }
    [ ! -e "$out/r.pfm" ] || { echo "$scene: an image was written"; exit 1; }
}
# reached SCENE PATTERN: the control, without the restriction the canary is
# opened (its contents are refused, or its MTL line read).
reached() {
    "$clpath" render "$1" "${small[@]}" -o "$out/c.pfm" >"$out/log" 2>&1 || true
    cat "$out/log"
    grep -q "$2" "$out/log" || { echo "$1: without --restrict-files the canary was not reached"; exit 1; }
}
for name in percent symlink; do
    reached "$out/jail/$name.gltf" "canary.png: cannot decode the image\\|link.png: cannot decode the image"
    refused "$out/jail/$name.gltf" canary.png
done
refused "$out/jail/absolute.gltf" canary.png  # a %2F-encoded absolute uri
reached "$out/jail/buffer.glb" "canary.bin"
refused "$out/jail/buffer.glb" canary.bin
for name in sub/dotdot absolute; do
    reached "$out/jail/$name.obj" "canary.mtl:1: Ns: 'canary' is not a number"
    refused "$out/jail/$name.obj" canary.mtl
done
# The scene file itself, and the environment variable for services.
rc=0
CLPATH_RESTRICT_FILES="$out/jail/sub" "$clpath" render "$out/jail/percent.gltf" "${small[@]}" -o "$out/r.pfm" >"$out/log" 2>&1 || rc=$?
cat "$out/log"
[ $rc -eq 1 ] && grep -q "resolves to $out/jail/percent.gltf, outside $out/jail/sub" "$out/log"
echo "every file outside the folder refused, each reached without the restriction"
