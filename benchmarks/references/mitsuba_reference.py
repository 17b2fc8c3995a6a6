"""Render a clpath export (clpath export SCENE OUT.json --format mitsuba) with
Mitsuba 3 as an independent reference: the mean of K renders with independent
seeds, and the variance that mean has.

    python mitsuba_reference.py OUT.json REF.exr --spp 1024 --seeds 16 [--variant llvm_ad_rgb]

Writes REF.exr (the mean, linear float RGB) and REF.var.exr: per pixel the
variance of ONE SAMPLE as the seeds estimate it (the spread of the K images
times spp), so that variance / (K spp) is the variance of REF.exr, which is
what an image entry of tests/robustness/reference_agreement_test.cpp reads;
its estimate has K - 1 degrees of freedom.

What the export leaves to this script ("clpath_" keys):
- look-at frames (camera, spot lights) become to_world transforms;
- a spot light's falloff: Mitsuba's own (linear in angle between beam width
  and cutoff) is switched off by the export (beam width = cutoff), and
  clpath's smoothstep(cos outer, cos inner, cos theta) is multiplied in as the
  spot's texture, sampled finely (bilinear between texels 1/2048 of the cone
  apart: the falloff is then off by less than 1e-5);
- textures ("clpath_texture": raw texels the export wrote beside the JSON)
  become float bitmaps: colour textures decoded from sRGB by Mitsuba's own
  conversion, one channel picked where clpath reads one (roughness G,
  metallic B, coverage A), the material's factor multiplied in, a normal
  map's scale applied to its x and y; the bitmap texture then filters and
  wraps them as clpath does (raw, bilinear or nearest, repeat/clamp/mirror);
- the glTF material's plugin, the threshold texture of alpha MASK and the
  product texture (base colour times vertex colours) come from gltf_bsdf.py;
- vertex colours ("clpath_vertex_colors": RGB floats per corner, in the OBJ's
  vertex order) become the shape's "vertex_color" attribute, which a
  mesh_attribute texture interpolates as clpath does;
- an environment image is turned to clpath's orientation and its texels are
  repeated 64x64 (Mitsuba interpolates between texel centres, clpath looks the
  nearest texel up; repeated texels confine the difference to seams 1/64 of
  a texel wide, and the ramp there averages to the step over any pixel that
  holds it whole).
"""
import argparse
import json
import math
import os
import sys
import time

if "DRJIT_LIBLLVM_PATH" not in os.environ:
    for cand in ("/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/aarch64-linux-gnu/libLLVM-19.so"):
        if os.path.exists(cand):
            os.environ["DRJIT_LIBLLVM_PATH"] = cand
            break

import numpy as np  # noqa: E402
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402


def fail(msg):
    print("mitsuba_reference.py: error: " + msg, file=sys.stderr)
    sys.exit(1)


def look_at(origin, target, up):
    return mi.ScalarTransform4f().look_at(origin=mi.ScalarPoint3f(origin), target=mi.ScalarPoint3f(target),
                                          up=mi.ScalarVector3f(up))


def spot_texture(inner_deg, outer_deg, n=2048):
    """clpath's spot falloff on Mitsuba's spot texture square: texel (u, v)
    looks along local (x, y, 1) with x = (2u - 1) tan(cutoff), y likewise."""
    ci, co = math.cos(math.radians(inner_deg)), math.cos(math.radians(outer_deg))
    t = math.tan(math.radians(outer_deg))
    c = (np.arange(n) + 0.5) / n * 2 - 1
    x, y = np.meshgrid(c * t, c * t)
    cos = 1 / np.sqrt(1 + x * x + y * y)
    if ci > co:
        s = np.clip((cos - co) / (ci - co), 0, 1)
        f = s * s * (3 - 2 * s)
    else:
        f = (cos >= ci).astype(np.float64)
    return np.repeat(f[:, :, None], 3, axis=2).astype(np.float32)


def env_to_world(rotation_deg):
    """to_world^-1 d must be clpath's rotated direction turned by 180 degrees
    about +y (clpath's u has 0.5 where Mitsuba's has 0)."""
    a = math.radians(rotation_deg)
    c, s = math.cos(a), math.sin(a)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    inv = np.diag([-1.0, 1, -1]) @ rot
    m = np.eye(4)
    m[:3, :3] = inv.T
    return mi.ScalarTransform4f(m.tolist())


def texture_bitmap(spec, folder):
    """The texels of one texture use as a float bitmap (see the docstring)."""
    path = os.path.join(folder, spec["file"])
    w, h = spec["width"], spec["height"]
    raw = np.fromfile(path, np.uint8 if spec["format"] == "rgba8" else "<f4")
    if raw.size != w * h * 4:
        fail("%s: %d values, expected %dx%dx4" % (path, raw.size, w, h))
    texels = raw.reshape(h, w, 4)
    ch = spec["channels"]
    if ch == "rgb":
        rgb = np.ascontiguousarray(texels[:, :, :3])
        if spec["srgb"]:
            bmp = mi.Bitmap(rgb, mi.Bitmap.PixelFormat.RGB)
            bmp.set_srgb_gamma(True)
            val = np.array(bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False))
        else:
            val = rgb.astype(np.float64) / (255.0 if spec["format"] == "rgba8" else 1.0)
        if "normal_scale" in spec:
            n = 2 * val - 1
            n[:, :, :2] *= spec["normal_scale"]
            val = (n + 1) / 2
    else:
        val = texels[:, :, "rgba".index(ch)][:, :, None].astype(np.float64)
        if spec["format"] == "rgba8":
            val = val / 255.0
    val = val * np.array(spec["scale"], dtype=np.float64)
    return mi.Bitmap(np.ascontiguousarray(val, dtype=np.float32))


def convert(d, folder):
    """The exported dictionary as mitsuba.load_dict takes it."""
    if isinstance(d, list):
        return [convert(x, folder) for x in d]
    if not isinstance(d, dict):
        return d
    out = {}
    for k, v in d.items():
        if k == "clpath_look_at":
            if "target" in v:
                out["to_world"] = look_at(v["origin"], v["target"], v["up"])
            else:
                dvec = np.array(v["direction"], dtype=float)
                up = [0, 1, 0] if abs(dvec[1]) < 0.9 * np.linalg.norm(dvec) else [1, 0, 0]
                out["to_world"] = look_at(v["origin"], list(np.array(v["origin"]) + dvec), up)
        elif k == "clpath_spot_falloff":
            out["texture"] = {"type": "bitmap", "bitmap": mi.Bitmap(spot_texture(v["inner_degrees"], v["outer_degrees"])),
                              "raw": True, "filter_type": "bilinear", "wrap_mode": "clamp"}
        elif k == "clpath_texture":
            out["bitmap"] = texture_bitmap(v, folder)
        elif k == "clpath_env_rotation_degrees":
            out["to_world"] = env_to_world(v)
        elif k == "filename" and d.get("type") == "envmap":
            path = v if os.path.isabs(v) else os.path.join(folder, v)
            img = np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False))
            img = np.repeat(np.repeat(img, 64, axis=0), 64, axis=1)
            out["bitmap"] = mi.Bitmap(img.astype(np.float32))
        elif k.startswith("clpath_"):
            fail("unknown marker " + k)
        else:
            out[k] = convert(v, folder)
    return out


def main():
    p = argparse.ArgumentParser(prog="mitsuba_reference.py")
    p.add_argument("scene", help="scene dictionary written by clpath export --format mitsuba")
    p.add_argument("out", help="output .exr (and OUT.var.exr beside it)")
    p.add_argument("--spp", type=int, default=1024, help="samples per pixel of each seed's render")
    p.add_argument("--seeds", type=int, default=16, help="independent renders (K >= 2)")
    p.add_argument("--seed0", type=int, default=0)
    p.add_argument("--variant", default="llvm_ad_rgb", help="llvm_ad_rgb (vectorised) or scalar_rgb")
    a = p.parse_args()
    if a.seeds < 2:
        fail("--seeds must be at least 2 (the variance comes from their spread)")
    mi.set_variant(a.variant)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import gltf_bsdf  # noqa: E402  (needs the variant set)
    gltf_bsdf.register()
    with open(a.scene) as f:
        js = json.load(f)
    if "scene" not in js or "clpath" not in js:
        fail(a.scene + ": not a file written by clpath export --format mitsuba")
    folder = os.path.dirname(os.path.abspath(a.scene))
    mi.file_resolver().prepend(folder)
    colours = {k: v.pop("clpath_vertex_colors") for k, v in js["scene"].items()
               if isinstance(v, dict) and "clpath_vertex_colors" in v}
    scene = mi.load_dict(convert(js["scene"], folder))
    for shape in scene.shapes():
        if shape.id() in colours:
            path = os.path.join(folder, colours.pop(shape.id()))
            rgb = np.fromfile(path, "<f4")
            if rgb.size != 3 * shape.vertex_count():
                fail("%s: %d values for a mesh of %d vertices" % (path, rgb.size, shape.vertex_count()))
            shape.add_attribute("vertex_color", 3, mi.Float(rgb))
    if colours:
        fail("no shape with the id " + ", ".join(colours))
    info = js["clpath"]
    t0 = time.time()
    s1 = s2 = None
    for k in range(a.seeds):
        img = np.array(mi.render(scene, spp=a.spp, seed=a.seed0 + k), dtype=np.float64)
        s1 = img if s1 is None else s1 + img
        s2 = img * img if s2 is None else s2 + img * img
        print("mitsuba_reference.py: seed %d of %d, %.0f s" % (k + 1, a.seeds, time.time() - t0), file=sys.stderr)
    K = a.seeds
    mean = s1 / K
    var_runs = np.maximum(s2 - K * mean * mean, 0) / (K - 1)  # spread of one seed's image
    mi.Bitmap(mean.astype(np.float32)).write(a.out)
    var_path = os.path.splitext(a.out)[0] + ".var.exr"
    mi.Bitmap((var_runs * a.spp).astype(np.float32)).write(var_path)
    print("mitsuba_reference.py: %s (%s): %dx%d, %d seeds x %d spp, Mitsuba %s %s, %s max_depth %d; "
          "image mean %s; %.0f s; wrote %s, %s"
          % (a.scene, info.get("name"), mean.shape[1], mean.shape[0], K, a.spp, mi.__version__, a.variant,
             js["scene"]["integrator"]["type"], js["scene"]["integrator"]["max_depth"], np.round(mean.mean(axis=(0, 1)), 6).tolist(), time.time() - t0,
             a.out, var_path))


main()
