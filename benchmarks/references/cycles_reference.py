"""Render a clpath export (clpath export SCENE OUT.json) with Blender Cycles as
an independent reference: a high-sample linear EXR.

    blender -b --factory-startup -P cycles_reference.py -- OUT.json REF.exr --samples 16384 [--threads 2] [--seed 0]

The settings are those an unbiased comparison with clpath needs:
- geometry from the OBJ as it is (no axis conversion), windings kept;
- materials from the MTL, rebuilt as a Lambertian Diffuse BSDF (roughness 0)
  of colour Kd plus an Emission of colour Ke and strength 1 (a mesh emitter of
  strength 1 has radiance equal to its colour, the unit of clpath's emission),
  emitting from the front face only unless the scene file marks it two-sided;
- a pinhole camera at the scene file's eye/target/up with its vertical field
  of view (sensor fit vertical), the same resolution;
- world black (or the scene file's constant environment colour);
- no clamping, no denoising, no adaptive sampling, no light threshold, no
  glossy blur; box pixel filter one pixel wide (clpath's uniform jitter in
  the pixel); bounce limits max_depth - 1 (Cycles counts bounces after the
  first hit: 0 is direct light only; clpath's max_depth counts scattering
  events); light sampling and MIS as Cycles does them;
- "Standard" view transform, and EXR written as scene-linear float.
"""
import argparse
import json
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_reference.py")
    p.add_argument("scene", help="scene file written by clpath export")
    p.add_argument("out", help="output .exr")
    p.add_argument("--samples", type=int, default=4096)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    return p.parse_args(argv)


def fail(msg):
    print("cycles_reference.py: error: " + msg, file=sys.stderr)
    sys.exit(1)


def read_mtl(path):
    """{name: {"Kd": (r, g, b), "Ke": (r, g, b)}} from the MTL clpath export writes."""
    mats, cur = {}, None
    with open(path) as f:
        for n, line in enumerate(f, 1):
            t = line.split()
            if not t or t[0].startswith("#"):
                continue
            if t[0] == "newmtl":
                cur = mats.setdefault(t[1], {"Kd": (0.8, 0.8, 0.8), "Ke": (0.0, 0.0, 0.0)})
            elif t[0] in ("Kd", "Ke"):
                if cur is None or len(t) != 4:
                    fail("%s:%d: %s outside a material or without three numbers" % (path, n, t[0]))
                cur[t[0]] = tuple(float(x) for x in t[1:4])
    return mats


def build_material(mat, albedo, emission, two_sided):
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*albedo, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    shader = diffuse.outputs["BSDF"]
    if max(emission) > 0:
        emit = nt.nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = (*emission, 1.0)
        emit.inputs["Strength"].default_value = 1.0
        if not two_sided:
            # Strength 1 - backfacing: nothing leaves the back of the winding.
            geo = nt.nodes.new("ShaderNodeNewGeometry")
            inv = nt.nodes.new("ShaderNodeMath")
            inv.operation = "SUBTRACT"
            inv.inputs[0].default_value = 1.0
            nt.links.new(geo.outputs["Backfacing"], inv.inputs[1])
            nt.links.new(inv.outputs["Value"], emit.inputs["Strength"])
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(diffuse.outputs["BSDF"], add.inputs[0])
        nt.links.new(emit.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
        # Sampled as a light (Cycles' mesh light sampling with MIS).
        if hasattr(mat.cycles, "sample_as_light"):
            mat.cycles.sample_as_light = True
        elif hasattr(mat.cycles, "emission_sampling"):
            mat.cycles.emission_sampling = "FRONT_BACK" if two_sided else "FRONT"
    nt.links.new(shader, out.inputs["Surface"])


def look_at(eye, target, up):
    """Blender cameras look down local -Z with +Y up; clpath's image right is
    forward x up, which is Blender's local +X for the same right-handed frame."""
    f = (target - eye).normalized()
    r = f.cross(up).normalized()
    u = r.cross(f)
    m = Matrix.Identity(4)
    for i in range(3):
        m[i][0], m[i][1], m[i][2], m[i][3] = r[i], u[i], -f[i], eye[i]
    return m


def main():
    a = parse_args()
    with open(a.scene) as f:
        sc = json.load(f)
    folder = os.path.dirname(os.path.abspath(a.scene))
    objs = sc.get("objects", [])
    if len(objs) != 1 or objs[0].get("type") != "mesh":
        fail(a.scene + ": expected one mesh object (a file written by clpath export)")
    obj_path = os.path.join(folder, objs[0]["file"])
    mtl_path = os.path.splitext(obj_path)[0] + ".mtl"
    mtl = read_mtl(mtl_path)
    overrides = {}  # MTL name -> scene material (two-sided emitters)
    for mtl_name, mat_name in objs[0].get("materials", {}).items():
        overrides[mtl_name] = sc["materials"][mat_name]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.wm.obj_import(filepath=obj_path, forward_axis="Y", up_axis="Z")
    for ob in scene.objects:
        ob.matrix_world = Matrix.Identity(4)  # clpath's coordinates, unconverted
        for slot in ob.material_slots:
            name = slot.material.name
            if name not in mtl:
                fail("%s: material '%s' is not in %s" % (obj_path, name, mtl_path))
            o = overrides.get(name)
            if o:
                build_material(slot.material, o.get("albedo", [0, 0, 0]), o["emission"], o.get("two_sided", False))
            else:
                build_material(slot.material, mtl[name]["Kd"], mtl[name]["Ke"], False)

    # Scene size, for the clipping range.
    lo, hi = Vector((1e30,) * 3), Vector((-1e30,) * 3)
    for ob in scene.objects:
        for v in ob.data.vertices:
            for i in range(3):
                lo[i], hi[i] = min(lo[i], v.co[i]), max(hi[i], v.co[i])
    cam_js = sc["camera"]
    eye, target = Vector(cam_js["eye"]), Vector(cam_js["target"])
    up = Vector(cam_js.get("up", [0, 1, 0]))
    diag = (hi - lo).length + (eye - (lo + hi) * 0.5).length
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(cam_js.get("vfov", 45.0))
    cam_data.clip_start = 1e-5 * diag
    cam_data.clip_end = 10 * diag
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    cam.matrix_world = look_at(eye, target, up)
    scene.camera = cam

    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    env = sc.get("environment", {}).get("color", [0, 0, 0])
    bg.inputs["Color"].default_value = (*env, 1.0)
    bg.inputs["Strength"].default_value = 1.0 if max(env) > 0 else 0.0
    scene.world = world

    w, h = cam_js.get("resolution", [640, 480])
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = w, h, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    r.use_border = False
    r.threads_mode = "FIXED"
    r.threads = a.threads
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = a.seed
    c.use_animated_seed = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    bounces = max(0, int(sc.get("render", {}).get("max_depth", 16)) - 1)
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.volume_bounces = 0
    c.transparent_max_bounces = bounces
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.caustics_reflective = c.caustics_refractive = True
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    img = r.image_settings
    img.file_format = "OPEN_EXR"
    img.color_mode = "RGB"
    img.color_depth = "32"
    img.exr_codec = "ZIP"

    tmp = a.out + ".tmp.exr"
    r.filepath = tmp
    r.use_file_extension = False
    print("cycles_reference.py: %s: %dx%d, %d samples, %d bounces, camera lens %.4f mm over a %.1f mm sensor height"
          % (a.scene, w, h, a.samples, bounces, cam_data.lens, cam_data.sensor_height))
    bpy.ops.render.render(write_still=True)
    if not os.path.exists(tmp):
        fail("Cycles wrote no image to " + tmp)
    os.replace(tmp, a.out)
    print("cycles_reference.py: wrote " + a.out)


main()
