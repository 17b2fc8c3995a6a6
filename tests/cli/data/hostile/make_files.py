#!/usr/bin/env python3
"""Writes the small hostile glTF files of the command-line tests into this
folder (run it again after changing it; the files are committed). Each is a
one-triangle model, broken in one way, named for what is wrong with it."""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def triangle():
    pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    return {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(pos),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": len(pos)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }


def glb(doc, version=2):
    text = json.dumps(doc).encode()
    text += b' ' * (-len(text) % 4)
    return (b'glTF' + struct.pack('<II', version, 20 + len(text)) + struct.pack('<I', len(text)) + b'JSON' + text)


def write(name, data):
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data if isinstance(data, bytes) else json.dumps(data, indent=1) + '\n')


write('glb-version-3.glb', glb(triangle(), 3))

d = triangle()
d["asset"]["version"] = "3.0"
write('asset-version-3.gltf', d)

d = triangle()
d["scenes"] = []
write('scenes-empty-scene-0.gltf', d)

perspective = {"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}
for name, ratio in [('aspect-ratio-0.gltf', 0), ('aspect-ratio-negative.gltf', -1.5)]:
    d = triangle()
    d["cameras"] = [json.loads(json.dumps(perspective))]
    d["cameras"][0]["perspective"]["aspectRatio"] = ratio
    d["nodes"].append({"camera": 0, "translation": [0.3, 0.3, 3]})
    d["scenes"][0]["nodes"].append(1)
    write(name, d)

d = triangle()
d["extensionsUsed"] = ["KHR_lights_punctual"]
d["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": "bright"}]}}
d["nodes"].append({"translation": [0, 0, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}})
d["scenes"][0]["nodes"].append(1)
write('light-intensity-string.gltf', d)

# Real files that must load: an orthographic camera, a skin without
# inverseBindMatrices, and an OBJ whose map_Kd file is missing.
d = triangle()
d["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 0.8, "ymag": 0.6, "znear": 0.1, "zfar": 10}}]
d["nodes"].append({"camera": 0, "translation": [0.4, 0.4, 3]})
d["scenes"][0]["nodes"].append(1)
write('orthographic-camera.gltf', d)

d = triangle()
d["nodes"] = [{"mesh": 0, "skin": 0}, {"name": "joint"}]
d["scenes"][0]["nodes"] = [0, 1]
d["skins"] = [{"joints": [1]}]
write('skin-without-inverse-bind-matrices.gltf', d)

with open(os.path.join(HERE, 'missing-map.obj'), 'w') as f:
    f.write('mtllib missing-map.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl wood\nf 1/1 2/2 3/3\n')
with open(os.path.join(HERE, 'missing-map.mtl'), 'w') as f:
    f.write('# a material whose image is not there\nnewmtl wood\nKd 0.8 0.6 0.4\nmap_Kd textures/wood.png\n')
