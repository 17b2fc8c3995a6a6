"""Writes the small glTF quads and textures of the glTF reference scenes
(../gltf-*.json) into this folder: every texel and vertex is computed here,
nothing comes from elsewhere. Python 3 standard library only.

    python3 make_gltf_assets.py
"""
import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(name, w, h, channels, texel):
    """An 8-bit PNG (RGB or RGBA) from texel(x, y) -> tuple of 0..255, row 0 at the top."""
    rows = b"".join(b"\0" + bytes(c for x in range(w) for c in texel(x, y)) for y in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    colour_type = 6 if channels == 4 else 2
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def byte(v):
    return max(0, min(255, int(round(v * 255))))


def quad(name, half_x, half_z, uv_range, material, images, sampler, nodes=None, roots=None):
    """A quad in the xz plane facing +y, u along +x and v along +z (so its
    UVs are not mirrored: glTF's bitangent sign +1), with one material;
    placed by one node, or by `nodes` (the scene's `roots` among them)."""
    (u0, u1), (v0, v1) = uv_range
    pos = [(-half_x, 0, -half_z), (-half_x, 0, half_z), (half_x, 0, half_z), (half_x, 0, -half_z)]
    uv = [(u0 + (p[0] + half_x) / (2 * half_x) * (u1 - u0), v0 + (p[2] + half_z) / (2 * half_z) * (v1 - v0)) for p in pos]
    idx = [0, 1, 2, 0, 2, 3]
    blob = (b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", 0, 1, 0) for _ in pos) +
            b"".join(struct.pack("<2f", *t) for t in uv) + struct.pack("<6H", *idx))
    doc = {
        "asset": {"version": "2.0", "generator": "clpath make_gltf_assets.py"},
        "scene": 0, "scenes": [{"nodes": roots or [0]}], "nodes": nodes or [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [material],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-half_x, 0, -half_z], "max": [half_x, 0, half_z]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    if images:
        doc["images"] = [{"uri": i} for i in images]
        doc["samplers"] = [sampler]
        doc["textures"] = [{"source": k, "sampler": 0} for k in range(len(images))]
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


LINEAR = 9729
REPEAT, CLAMP, MIRROR = 10497, 33071, 33648


def main():
    # Base colours (sRGB bytes): a checker of 4x4-texel cells, and a ramp.
    png("checker.png", 16, 16, 3, lambda x, y: (230, 215, 180) if (x // 4 + y // 4) % 2 else (50, 90, 150))
    png("ramp.png", 16, 8, 3, lambda x, y: (byte(x / 15), byte(0.3 + 0.5 * y / 7), byte(1 - x / 15)))
    # Metallic-roughness: roughness (G) in stripes 0.25..0.75, metallic (B) 1.
    png("rough-stripes.png", 16, 16, 3, lambda x, y: (0, byte(0.25 + 0.5 * ((x // 4) % 4) / 3), 255))
    # Metallic (B) ramping 0..1 along u, roughness (G) 0.4.
    png("metal-ramp.png", 16, 4, 3, lambda x, y: (0, byte(0.4), byte(x / 15)))
    # Coverage: round holes (alpha 0) in an opaque sheet, base colour warm.
    def holes(x, y):
        cx, cy = x % 8 - 3.5, y % 8 - 3.5
        return (200, 120, 60, 0 if cx * cx + cy * cy < 7 else 255)
    png("holes.png", 16, 16, 4, holes)
    # Tangent-space normals of h = 0.5 sin(2 pi x / 8) sin(2 pi y / 8) (texels),
    # +y of tangent space towards the top row (glTF).
    def bumps(x, y):
        k = 2 * math.pi / 8
        dx = 0.5 * k * math.cos(k * (x + 0.5)) * math.sin(k * (y + 0.5))
        dy = -0.5 * k * math.sin(k * (x + 0.5)) * math.cos(k * (y + 0.5))  # d/d(up) = -d/d(row)
        n = (-dx, -dy, 1.0)
        ln = math.sqrt(sum(c * c for c in n))
        return tuple(byte(0.5 + 0.5 * c / ln) for c in n)
    png("bumps.png", 16, 16, 3, bumps)
    # Layer weights (R, linear) in four stripes along u: 0.25, 0.5, 0.75, 1; roughness (G) 0.5 .. 1.
    png("layer-stripes.png", 16, 4, 3, lambda x, y: (byte(0.25 * (x // 4 + 1)), byte(0.5 + 0.5 * (x // 4) / 3), 0))

    def mat(name, **kw):
        m = {"name": name, "pbrMetallicRoughness": {}}
        pbr = m["pbrMetallicRoughness"]
        for k in ("baseColorFactor", "metallicFactor", "roughnessFactor"):
            if k in kw:
                pbr[k] = kw.pop(k)
        if "base" in kw:
            pbr["baseColorTexture"] = {"index": kw.pop("base")}
        if "mr" in kw:
            pbr["metallicRoughnessTexture"] = {"index": kw.pop("mr")}
        if "normal" in kw:
            m["normalTexture"] = {"index": kw.pop("normal"), "scale": kw.pop("normal_scale", 1.0)}
        m.update(kw)
        return m

    rep = {"magFilter": LINEAR, "minFilter": LINEAR, "wrapS": REPEAT, "wrapT": REPEAT}
    # (a) base colour textures, metallic 0: repeat, clamp, mirrored repeat.
    quad("checker-floor.gltf", 2, 2, ((0, 3), (0, 3)), mat("checker", metallicFactor=0, roughnessFactor=0.5, base=0),
         ["checker.png"], rep)
    quad("ramp-clamp.gltf", 0.6, 0.4, ((-0.25, 1.25), (-0.25, 1.25)),
         mat("ramp clamped", metallicFactor=0, roughnessFactor=0.3, base=0), ["ramp.png"],
         dict(rep, wrapS=CLAMP, wrapT=CLAMP))
    quad("checker-mirror.gltf", 0.4, 0.4, ((0, 2.5), (0, 2.5)),
         mat("checker mirrored", metallicFactor=0, roughnessFactor=0.7, baseColorFactor=[1, 0.8, 0.8, 1], base=0),
         ["checker.png"], dict(rep, wrapS=MIRROR, wrapT=MIRROR))
    # (b) metallic 1 with a roughness texture; metallic from a texture.
    quad("gold-stripes.gltf", 0.6, 0.45, ((0, 1), (0, 1)),
         mat("gold stripes", metallicFactor=1, roughnessFactor=1, baseColorFactor=[1, 0.78, 0.34, 1], mr=0),
         ["rough-stripes.png"], rep)
    quad("metal-ramp.gltf", 0.6, 0.3, ((0, 1), (0, 1)),
         mat("metal ramp", metallicFactor=1, roughnessFactor=1, baseColorFactor=[0.9, 0.5, 0.4, 1], mr=0),
         ["metal-ramp.png"], dict(rep, wrapS=CLAMP, wrapT=CLAMP))
    # (c) an alpha MASK cut-out.
    quad("holes.gltf", 0.6, 0.6, ((0, 2), (0, 2)),
         mat("perforated", metallicFactor=0, roughnessFactor=0.6, base=0, alphaMode="MASK", alphaCutoff=0.5,
             doubleSided=True), ["holes.png"], rep)
    # (d) a normal map (scale 0.8).
    quad("bumps.gltf", 0.8, 0.6, ((0, 2), (0, 1.5)),
         mat("bumpy", metallicFactor=0, roughnessFactor=0.35, baseColorFactor=[0.7, 0.75, 0.8, 1], normal=0,
             normal_scale=0.8), ["bumps.png"], rep)
    # (d') the same normal-mapped quad, and the checker, each placed by two
    # nodes (the renderer stores each mesh once and places it by instances):
    # bumps side by side, the second turned in its plane under a parent's
    # non-uniform scale (its tangents sheared: they move with the transform,
    # not with its inverse transpose); checkers side by side, the second
    # mirrored. No mirrored normal map: Mitsuba's normalmap builds its
    # frame as cross(n, dp/du), the bitangent sign +1 only.
    turn = [0, math.sin(math.radians(17.5)), 0, math.cos(math.radians(17.5))]
    quad("bumps-pair.gltf", 0.8, 0.6, ((0, 2), (0, 1.5)),
         mat("bumpy", metallicFactor=0, roughnessFactor=0.35, baseColorFactor=[0.7, 0.75, 0.8, 1], normal=0,
             normal_scale=0.8), ["bumps.png"], rep,
         nodes=[{"mesh": 0, "translation": [-0.45, 0, 0], "scale": [0.5, 1, 0.5]},
                {"translation": [0.45, 0, 0], "scale": [0.6, 1, 0.35], "children": [2]},
                {"mesh": 0, "rotation": turn}], roots=[0, 1])
    quad("checker-pair.gltf", 0.4, 0.4, ((0, 2.5), (0, 2.5)),
         mat("checker", metallicFactor=0, roughnessFactor=0.5, base=0), ["checker.png"], rep,
         nodes=[{"mesh": 0, "translation": [-0.45, 0, 0]},
                {"mesh": 0, "translation": [0.45, 0, 0], "scale": [-1, 1, 1]}], roots=[0, 1])
    # (e) KHR_materials_clearcoat: a coat of weight and roughness from stripes
    # over dark red plastic (car paint: the coat dominates); a smooth full coat over a rough metal.
    quad("coat-stripes.gltf", 0.6, 0.45, ((0, 1), (0, 1)),
         mat("coat stripes", metallicFactor=0, roughnessFactor=0.6, baseColorFactor=[0.1, 0.02, 0.015, 1],
             extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatTexture": {"index": 0},
                                                     "clearcoatRoughnessFactor": 0.3,
                                                     "clearcoatRoughnessTexture": {"index": 0}}}),
         ["layer-stripes.png"], dict(rep, wrapS=CLAMP, wrapT=CLAMP))
    quad("coated-metal.gltf", 0.6, 0.3, ((0, 1), (0, 1)),
         mat("coated metal", metallicFactor=1, roughnessFactor=0.5, baseColorFactor=[0.3, 0.45, 0.8, 1],
             extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}),
         [], None)
    # (f) KHR_materials_transmission, thin-walled: rough clear glass, and a
    # tinted pane whose transmission comes in stripes.
    quad("thin-glass.gltf", 0.5, 0.45, ((0, 1), (0, 1)),
         mat("thin glass", metallicFactor=0, roughnessFactor=0.25, baseColorFactor=[0.95, 0.97, 1.0, 1],
             doubleSided=True, extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0}}),
         [], None)
    quad("tinted-stripes.gltf", 0.5, 0.45, ((0, 1), (0, 1)),
         mat("tinted stripes", metallicFactor=0, roughnessFactor=0.5, baseColorFactor=[0.4, 0.85, 0.5, 1],
             doubleSided=True, extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0,
                                                                          "transmissionTexture": {"index": 0}}}),
         ["layer-stripes.png"], dict(rep, wrapS=CLAMP, wrapT=CLAMP))


main()
