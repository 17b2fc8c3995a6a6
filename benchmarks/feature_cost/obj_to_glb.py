#!/usr/bin/env python3
"""Writes a binary glTF (.glb) from an OBJ of triangles, as a glTF exporter
would: shared vertices (corners with the same position merged), an unsigned
int index buffer, area-weighted vertex normals and planar texture coordinates,
one mesh, one node. For the load-time benchmark (run.sh): the glb is made here
rather than kept in the repository, since a million triangles take ~40 MB.

Usage: obj_to_glb.py in.obj out.glb [out.gltf]
With out.gltf, the same model is also written as a .gltf whose buffer is a
base64 data URI (as some exporters write single-file glTF).
Python standard library only (Debian's python3)."""
import array
import base64
import json
import math
import struct
import sys


def read_obj(path):
    positions = array.array("f")
    corners = array.array("I")
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                x, y, z = line.split()[1:4]
                positions.extend((float(x), float(y), float(z)))
            elif line.startswith("f "):
                refs = [int(t.split("/")[0]) for t in line.split()[1:]]
                count = len(positions) // 3
                refs = [r - 1 if r > 0 else count + r for r in refs]
                for i in range(1, len(refs) - 1):  # a fan, for polygons
                    corners.extend((refs[0], refs[i], refs[i + 1]))
    return positions, corners


def merge_vertices(positions, corners):
    """One vertex per distinct position, as indexed glTF meshes have."""
    seen = {}
    out = array.array("f")
    remap = array.array("I", bytes(4 * (len(positions) // 3)))
    for i in range(len(positions) // 3):
        key = (positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
        j = seen.get(key)
        if j is None:
            j = len(seen)
            seen[key] = j
            out.extend(key)
        remap[i] = j
    return out, array.array("I", (remap[c] for c in corners))


def vertex_normals(p, idx):
    n = array.array("f", bytes(len(p) * 4))
    for t in range(0, len(idx), 3):
        a, b, c = idx[t], idx[t + 1], idx[t + 2]
        ax, ay, az = p[3 * a], p[3 * a + 1], p[3 * a + 2]
        ux, uy, uz = p[3 * b] - ax, p[3 * b + 1] - ay, p[3 * b + 2] - az
        vx, vy, vz = p[3 * c] - ax, p[3 * c + 1] - ay, p[3 * c + 2] - az
        cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        for v in (a, b, c):
            n[3 * v] += cx
            n[3 * v + 1] += cy
            n[3 * v + 2] += cz
    for v in range(len(p) // 3):
        x, y, z = n[3 * v], n[3 * v + 1], n[3 * v + 2]
        length = math.sqrt(x * x + y * y + z * z)
        if length > 0:
            n[3 * v], n[3 * v + 1], n[3 * v + 2] = x / length, y / length, z / length
        else:
            n[3 * v + 1] = 1.0
    return n


def bounds(p):
    return ([min(p[k::3]) for k in range(3)], [max(p[k::3]) for k in range(3)])


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: obj_to_glb.py in.obj out.glb [out.gltf]")
    positions, corners = read_obj(sys.argv[1])
    p, idx = merge_vertices(positions, corners)
    n = vertex_normals(p, idx)
    lo, hi = bounds(p)
    span = [max(h - l, 1e-12) for l, h in zip(lo, hi)]
    uv = array.array("f")
    for v in range(len(p) // 3):
        uv.extend(((p[3 * v] - lo[0]) / span[0], (p[3 * v + 2] - lo[2]) / span[2]))
    count = len(p) // 3
    blobs = [idx.tobytes(), p.tobytes(), n.tobytes(), uv.tobytes()]
    views, offset = [], 0
    for b in blobs:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(b)})
        offset += len(b)
    doc = {
        "asset": {"version": "2.0", "generator": "clpath benchmarks/feature_cost/obj_to_glb.py"},
        "buffers": [{"byteLength": offset}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5125, "count": len(idx), "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 3, "componentType": 5126, "count": count, "type": "VEC2"},
        ],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1],
                                                                "metallicFactor": 0, "roughnessFactor": 0.6}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1, "NORMAL": 2, "TEXCOORD_0": 3},
                                    "indices": 0, "material": 0}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    body = b"".join(blobs)
    body += b"\0" * (-len(body) % 4)
    total = 12 + 8 + len(js) + 8 + len(body)
    with open(sys.argv[2], "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(js), b"JSON") + js)
        f.write(struct.pack("<I4s", len(body), b"BIN\0") + body)
    print(f"{sys.argv[2]}: {len(idx) // 3} triangles, {count} vertices, {total} bytes")
    if len(sys.argv) == 4:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(body[:offset]).decode()
        with open(sys.argv[3], "w") as f:
            json.dump(doc, f, separators=(",", ":"))
        print(f"{sys.argv[3]}: the same with the buffer as a data URI")


if __name__ == "__main__":
    main()
