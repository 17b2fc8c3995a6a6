// The JSON scene format: what a valid file gives, and that every kind of bad
// input is refused with a message naming the file and the line or field.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/load/load_options.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/load/scene_loader.hpp"
#include "scene/memory_files.hpp"
#include "support/temp_paths.hpp"

namespace clpath {
namespace {

using test::error_of;
using test::MemoryFiles;

const char* kCamera = R"("camera": {"eye": [0, 0, -3], "target": [0, 0, 0]})";
const char* kMaterials = R"("materials": {"white": {"type": "diffuse"}, "lamp": {"type": "emitter", "emission": 4}})";

// A valid scene around the given objects (and optional extra top-level fields).
std::string scene_with(const std::string& objects, const std::string& extra = "") {
    return std::string("{") + kCamera + ", " + kMaterials + ", \"objects\": [" + objects + "]" +
           (extra.empty() ? "" : ", " + extra) + "}";
}

Scene parse(const std::string& text, const MemoryFiles& files = {}) {
    return parse_scene_file(text, "scenes/s.json", files.options());
}

std::string parse_error(const std::string& text, const MemoryFiles& files = {}) {
    return error_of([&] { parse(text, files); });
}

const char* kPlane = R"({"type": "plane", "material": "white"})";

TEST(SceneFile, MinimalSceneTakesTheDocumentedDefaults) {
    const Scene s = parse(scene_with(kPlane));
    EXPECT_EQ(s.name, "s");
    EXPECT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(s.camera.vfov_degrees, 45.0f);
    EXPECT_EQ(s.camera.width, 640);
    EXPECT_EQ(s.camera.height, 480);
    EXPECT_EQ(s.render.spp, 64u);
    EXPECT_EQ(s.render.integrator, "path");
    ASSERT_EQ(s.material_names.size(), 2u);
    EXPECT_EQ(s.material_names[0], "white");  // file order is kept
    EXPECT_FLOAT_EQ(s.materials[0].albedo[0], 0.8f);
    EXPECT_EQ(s.materials[0].kind, CLP_MAT_DIFFUSE);
    EXPECT_FLOAT_EQ(s.materials[1].emission[1], 4.0f);
    EXPECT_FLOAT_EQ(s.materials[1].albedo[0], 0.0f);
    EXPECT_TRUE(s.normals.empty());
    EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneFile, ReadsEveryField) {
    const std::string text = R"({
      "name": "everything", "description": "all fields",
      "camera": {"eye": [1, 2, 3], "target": [1, 3, 3], "up": [0, 0, 1], "vfov": 30, "resolution": [320, 200]},
      "render": {"spp": 9, "max_depth": 3, "russian_roulette": "depth", "integrator": "ao", "seed": 7, "ao_distance": 0.5,
                 "light_sampler": "bvh"},
      "materials": {
        "d": {"type": "diffuse", "color": [0.1, 0.2, 0.3], "emission": [1, 2, 3], "two_sided": true},
        "e": {"type": "emitter", "radiance": 2, "strength": 10, "albedo": 0.5},
        "m": {"type": "mirror", "tint": [0.9, 0.8, 0.7]},
        "c": {"type": "glossy", "f0": 0.95, "roughness": 0.09},
        "g": {"type": "glass", "ior": 1.51714, "tint": [0.5, 0.5, 0.9], "roughness": 0.2}
      },
      "objects": [
        {"type": "plane", "material": "d", "size": [2, 3]},
        {"type": "box", "material": "e", "size": [1, 2, 3], "transform": {"translate": [5, 0, 0]}},
        {"type": "icosphere", "material": "m", "radius": 2, "subdivisions": 0},
        {"type": "sphere", "material": "c", "triangles": 196, "displacement": {"amplitude": 0.1, "frequency": 2}},
        {"type": "grid", "material": "g", "resolution": [3, 4], "height": {"function": "ripple", "amplitude": 0.1}}
      ],
      "lights": [
        {"type": "point", "position": [0, 5, 0], "intensity": [1, 2, 3]},
        {"type": "spot", "position": [0, 5, 0], "target": [0, 0, 0], "intensity": 5, "inner_angle": 10, "outer_angle": 20},
        {"type": "directional", "direction": [0, -2, 0], "intensity": 3}
      ],
      "environment": {"color": [0.1, 0.2, 0.3]}
    })";
    const Scene s = parse(text);
    EXPECT_EQ(s.name, "everything");
    EXPECT_EQ(s.camera.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.camera.up, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.camera.width, 320);
    EXPECT_EQ(s.render.spp, 9u);
    EXPECT_EQ(s.render.max_depth, 3u);
    EXPECT_EQ(s.render.russian_roulette, "depth");
    EXPECT_EQ(s.render.integrator, "ao");
    EXPECT_EQ(s.render.seed, 7u);
    EXPECT_FLOAT_EQ(s.render.ao_distance, 0.5f);
    EXPECT_EQ(s.render.light_sampler, "bvh");

    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_FLOAT_EQ(s.materials[0].albedo[2], 0.3f);
    EXPECT_FLOAT_EQ(s.materials[0].emission[2], 3.0f);
    EXPECT_EQ(s.materials[0].flags, CLP_MATF_TWO_SIDED_EMISSION);
    EXPECT_FLOAT_EQ(s.materials[1].emission[0], 20.0f);
    EXPECT_FLOAT_EQ(s.materials[1].albedo[0], 0.5f);
    EXPECT_EQ(s.materials[2].kind, CLP_MAT_MIRROR);
    EXPECT_EQ(s.materials[3].kind, CLP_MAT_CONDUCTOR);
    EXPECT_FLOAT_EQ(s.materials[3].roughness, 0.09f);
    EXPECT_FLOAT_EQ(s.materials[3].albedo[1], 0.95f);
    EXPECT_EQ(s.materials[4].kind, CLP_MAT_DIELECTRIC);
    EXPECT_FLOAT_EQ(s.materials[4].ior, 1.51714f);
    EXPECT_FLOAT_EQ(s.materials[4].albedo[2], 0.9f);

    // plane 2 + box 12 + icosahedron 20 + sphere 196 (8 rings, 14 segments) + grid 24
    EXPECT_EQ(s.triangle_count(), 2u + 12u + 20u + 196u + 24u);

    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, PunctualLight::Type::Point);
    EXPECT_EQ(s.lights[0].intensity, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[1].type, PunctualLight::Type::Spot);
    EXPECT_NEAR(s.lights[1].direction.y, -1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(s.lights[1].spot_outer_degrees, 20.0f);
    EXPECT_EQ(s.lights[2].type, PunctualLight::Type::Directional);
    EXPECT_EQ(s.lights[2].direction, glm::vec3(0, -1, 0));  // normalised
    EXPECT_EQ(s.environment.color, glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST(SceneFile, TransformIsTranslateRotateScaleWithRotationsInDegrees) {
    // A unit box scaled by (2, 1, 1), turned 90 degrees about z (x goes to y), moved up 10.
    const Scene s = parse(scene_with(
        R"({"type": "box", "material": "white", "transform": {"translate": [0, 10, 0], "rotate": [0, 0, 90], "scale": [2, 1, 1]}})"));
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (auto v : s.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    EXPECT_NEAR(lo.x, -0.5f, 1e-5f);
    EXPECT_NEAR(hi.x, 0.5f, 1e-5f);
    EXPECT_NEAR(lo.y, 9.0f, 1e-5f);
    EXPECT_NEAR(hi.y, 11.0f, 1e-5f);
}

TEST(SceneFile, MirroringScaleKeepsTrianglesFacingOut) {
    const Scene s = parse(scene_with(R"({"type": "box", "material": "white", "transform": {"scale": [-1, 1, 1]}})"));
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        const glm::vec3 a = s.vertices[3 * t], b = s.vertices[3 * t + 1], c = s.vertices[3 * t + 2];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f), 0.0f) << "triangle " << t;
    }
}

TEST(SceneFile, SmoothObjectGivesNormalsToEveryTriangle) {
    const Scene s = parse(scene_with(std::string(kPlane) + R"(, {"type": "icosphere", "material": "white", "smooth": true, "subdivisions": 1, "radius": 2, "transform": {"translate": [5, 0, 0]}})"));
    ASSERT_EQ(s.normals.size(), s.vertices.size());
    EXPECT_EQ(s.normals[0], glm::vec3(0, 1, 0));  // the plane, flat
    for (std::size_t i = 6; i < s.vertices.size(); ++i) {
        const glm::vec3 expect = glm::normalize(s.vertices[i] - glm::vec3(5, 0, 0));
        EXPECT_NEAR(glm::dot(s.normals[i], expect), 1.0f, 1e-5f);
    }
}

TEST(SceneFile, RelativePathsAreRelativeToTheSceneFile) {
    MemoryFiles files;
    files.files["scenes/meshes/tri.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const Scene s = parse(scene_with(R"({"type": "mesh", "file": "meshes/tri.obj", "material": "white"},
                                       {"type": "mesh", "file": "meshes/tri.obj"})"),
                          files);
    EXPECT_EQ(s.triangle_count(), 2u);
    // The second use has no material: the mesh's default, added once.
    EXPECT_EQ(s.material_names.back(), "scenes/meshes/tri.obj:(default)");
}

TEST(SceneFile, SceneMaterialsOverrideTheMeshOwn) {
    MemoryFiles files;
    files.files["scenes/m.obj"] =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\nusemtl blue\nf 1 3 2\n";
    files.files["scenes/m.mtl"] = "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
    // The MTL's own.
    Scene s = parse(scene_with(R"({"type": "mesh", "file": "m.obj"})"), files);
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.material_names[s.triangle_material[0]], "scenes/m.obj:red");
    EXPECT_FLOAT_EQ(s.materials[s.triangle_material[1]].albedo[2], 1.0f);
    // One by name.
    s = parse(scene_with(R"({"type": "mesh", "file": "m.obj", "materials": {"blue": "lamp"}})"), files);
    EXPECT_EQ(s.material_names[s.triangle_material[0]], "scenes/m.obj:red");
    EXPECT_EQ(s.material_names[s.triangle_material[1]], "lamp");
    // All.
    s = parse(scene_with(R"({"type": "mesh", "file": "m.obj", "material": "white"})"), files);
    EXPECT_EQ(s.triangle_material[0], 0u);
    EXPECT_EQ(s.triangle_material[1], 0u);
    // A name the mesh does not use is a mistake.
    EXPECT_EQ(parse_error(scene_with(R"({"type": "mesh", "file": "m.obj", "materials": {"green": "lamp"}})"), files),
              "scenes/s.json: objects[0].materials.green: the mesh scenes/m.obj uses no material named 'green'");
}

TEST(SceneFile, UndefinedUsemtlIsGreyWithAWarningUnlessTheSceneGivesIt) {
    MemoryFiles files;
    files.files["scenes/m.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n";
    const Scene grey = parse(scene_with(R"({"type": "mesh", "file": "m.obj"})"), files);
    ASSERT_FALSE(grey.warnings.empty());
    EXPECT_EQ(grey.warnings[0], "scenes/m.obj:4: usemtl 'paint': no .mtl file defines it, and scenes/s.json: objects[0] "
                                "gives no material for it (\"material\" or \"materials\"); it is the default grey");
    EXPECT_EQ(grey.material_names[grey.triangle_material[0]], "scenes/m.obj:(default)");
    const Scene s = parse(scene_with(R"({"type": "mesh", "file": "m.obj", "materials": {"paint": "white"}})"), files);
    EXPECT_EQ(s.triangle_material[0], 0u);
}

TEST(SceneFile, NoEmitterLoadsAndSaysSo) {
    const Scene s = parse(scene_with(kPlane));
    EXPECT_FALSE(s.has_emitter());
    const Scene lit = parse(scene_with(R"({"type": "plane", "material": "lamp"})"));
    EXPECT_TRUE(lit.has_emitter());
}

TEST(SceneFile, DegenerateTrianglesAreDroppedWithOneWarning) {
    const Scene s = parse(scene_with(std::string(kPlane) +
                                     R"(, {"type": "box", "material": "white", "transform": {"scale": [0, 1, 1]}})"));
    // Flattened to x = 0, the box keeps its two x faces; the other eight triangles have no area.
    EXPECT_EQ(s.triangle_count(), 2u + 4u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.warnings[0], "dropped 8 degenerate triangles (zero area or non-finite vertices): scenes/s.json: objects[1]: 8");
}

TEST(SceneFile, EnvironmentImagePathIsCheckedAndResolved) {
    MemoryFiles files;
    files.files["scenes/sky.exr"] = "";
    const Scene s = parse(scene_with(kPlane, R"("environment": {"image": "sky.exr", "scale": 2, "rotation": 90, "importance_sampled": false})"), files);
    EXPECT_EQ(s.environment.image, "scenes/sky.exr");
    EXPECT_FLOAT_EQ(s.environment.scale, 2.0f);
    EXPECT_FALSE(s.environment.importance_sampled);
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("environment": {"image": "none.exr"})"), files),
              "scenes/s.json: environment.image: scenes/none.exr: no such file");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("environment": {"color": 1, "scale": 2})")),
              "scenes/s.json: environment.scale: only an environment image takes this field");
}

// --- bad input --------------------------------------------------------------

TEST(SceneFileBad, SyntaxErrorNamesLineAndColumn) {
    const std::string msg = parse_error("{\n  \"camera\": {\n    \"eye\": [0, 0 0]\n  }\n}\n");
    EXPECT_EQ(msg.rfind("scenes/s.json:3:18: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("syntax error"), std::string::npos) << msg;
    EXPECT_EQ(parse_error("").rfind("scenes/s.json:1:1: ", 0), 0u);
    EXPECT_EQ(parse_error("{\"a\": tru}").rfind("scenes/s.json:1:", 0), 0u);
}

TEST(SceneFileBad, NumberTooLargeForJson) {
    const std::string msg = parse_error(scene_with(kPlane, R"("render": {"ao_distance": 1e999})"));
    EXPECT_EQ(msg.rfind("scenes/s.json", 0), 0u) << msg;
}

TEST(SceneFileBad, UnknownFieldsAreNamedByPath) {
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("lighting": [])")),
              "scenes/s.json: lighting: unknown field (allowed here: camera, description, environment, lights, "
              "materials, name, objects, render)");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "box", "material": "white", "transform": {"scle": 2}})")),
              "scenes/s.json: objects[0].transform.scle: unknown field (allowed here: rotate, scale, translate)");
    // A field of another shape or material type is unknown here too.
    EXPECT_NE(parse_error(scene_with(R"({"type": "plane", "material": "white", "subdivisions": 2})"))
                  .find("objects[0].subdivisions: unknown field"),
              std::string::npos);
    EXPECT_NE(parse_error(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0]}, "materials": {"x": {"type": "diffuse", "ior": 1.5}}, "objects": []})")
                  .find("scenes/s.json: materials.x.ior: unknown field"),
              std::string::npos);
}

TEST(SceneFileBad, KeyGivenTwice) {
    EXPECT_EQ(parse_error(scene_with(R"({"type": "plane", "material": "white", "material": "lamp"})")),
              "scenes/s.json: objects[0].material: field given twice");
}

TEST(SceneFileBad, WrongTypes) {
    EXPECT_EQ(parse_error(R"({"camera": {"eye": [0, 0, -1], "target": [0, 0, 0], "vfov": "wide"}})"),
              "scenes/s.json: camera.vfov: expected a number, got string");
    EXPECT_EQ(parse_error(R"({"camera": {"eye": [0, 0], "target": [0, 0, 0]}})"),
              "scenes/s.json: camera.eye: expected an array of three numbers [x, y, z], got an array of 2");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("render": {"spp": 2.5})")),
              "scenes/s.json: render.spp: expected an integer, got 2.5");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "icosphere", "material": "white", "smooth": 1})")),
              "scenes/s.json: objects[0].smooth: expected true or false, got number");
    EXPECT_EQ(parse_error("[1, 2]"), "scenes/s.json: expected an object { ... }, got array");
    EXPECT_EQ(parse_error(scene_with(R"({"type": 3})")), "scenes/s.json: objects[0].type: expected a string, got number");
}

TEST(SceneFile, CameraTakesAThinLens) {
    const std::string objects = R"(, "materials": {"x": {"type": "diffuse"}}, "objects": [{"type": "plane", "material": "x"}]})";
    const Scene s = parse(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0], "aperture_radius": 0.05, "focus_distance": 3})" +
                          objects);
    EXPECT_FLOAT_EQ(s.camera.aperture_radius, 0.05f);
    EXPECT_FLOAT_EQ(s.camera.focus_distance, 3.0f);
    const Scene pinhole = parse(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0]})" + objects);
    EXPECT_FALSE(pinhole.camera.has_lens());
    EXPECT_EQ(parse_error(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0], "aperture_radius": -1})" + objects),
              "scenes/s.json: camera.aperture_radius: -1 is out of range (must be >= 0)");
    EXPECT_EQ(parse_error(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0], "focus_distance": 0})" + objects),
              "scenes/s.json: camera.focus_distance: 0 is out of range (must be > 0)");
}

TEST(SceneFileBad, OutOfRangeValues) {
    auto material = [](const std::string& m) {
        return parse_error(R"({"camera": {"eye": [0,0,-1], "target": [0,0,0]}, "materials": {"x": )" + m +
                           R"(}, "objects": [{"type": "plane", "material": "x"}]})");
    };
    EXPECT_EQ(material(R"({"type": "diffuse", "albedo": [-0.1, 0, 0]})"),
              "scenes/s.json: materials.x.albedo[0]: -0.1 is out of range (must be [0, 1])");
    EXPECT_EQ(material(R"({"type": "diffuse", "albedo": 1.5})"),
              "scenes/s.json: materials.x.albedo: 1.5 is out of range (must be [0, 1])");
    EXPECT_EQ(material(R"({"type": "glass", "ior": 0})"), "scenes/s.json: materials.x.ior: 0 is out of range (must be (0, 100])");
    EXPECT_EQ(material(R"({"type": "glossy", "roughness": 1.5})"),
              "scenes/s.json: materials.x.roughness: 1.5 is out of range (must be [0, 1])");
    EXPECT_EQ(material(R"({"type": "emitter", "emission": -1})"),
              "scenes/s.json: materials.x.emission: -1 is out of range (must be >= 0)");
    EXPECT_EQ(material(R"({"type": "emitter"})"), "scenes/s.json: materials.x.emission: required for an emitter");
    EXPECT_EQ(material(R"({"type": "plastic"})"),
              "scenes/s.json: materials.x.type: unknown material type 'plastic' (choose one of: diffuse, mirror, "
              "conductor, dielectric, or the aliases emitter (diffuse of albedo 0 that emits), glossy (conductor), "
              "glass (dielectric))");
    EXPECT_EQ(material(R"({"type": "diffuse", "albedo": 0.5, "color": 0.5})"),
              "scenes/s.json: materials.x.color: give only one of 'albedo' and 'color' (they mean the same)");

    auto camera = [](const std::string& c) { return parse_error(R"({"camera": )" + c + "}"); };
    EXPECT_EQ(camera(R"({"eye": [0,0,-1], "target": [0,0,0], "vfov": 180})"),
              "scenes/s.json: camera.vfov: 180 is out of range (must be (0, 180))");
    EXPECT_EQ(camera(R"({"eye": [0,0,-1], "target": [0,0,0], "resolution": [0, 10]})"),
              "scenes/s.json: camera.resolution[0]: 0 is out of range (must be in [1, 16384])");
    EXPECT_EQ(camera(R"({"eye": [0,0,-1], "target": [0,0,0], "resolution": [10, 16385]})"),
              "scenes/s.json: camera.resolution[1]: 16385 is out of range (must be in [1, 16384])");
    EXPECT_EQ(camera(R"({"eye": [0,0,0], "target": [0,0,0]})"),
              "scenes/s.json: camera: eye and target must be distinct finite points");
    EXPECT_EQ(camera(R"({"eye": [0,0,0], "target": [0,1,0]})"),
              "scenes/s.json: camera: up must not be parallel to the view direction");
    EXPECT_EQ(camera(R"({"eye": [1e31,0,0], "target": [0,1,0]})"),
              "scenes/s.json: camera.eye[0]: 1e+31 is out of range (must be any finite number)");

    EXPECT_EQ(parse_error(scene_with(kPlane, R"("render": {"spp": 0})")),
              "scenes/s.json: render.spp: 0 is out of range (must be in [1, 4294967295])");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("render": {"integrator": "magic"})")),
              "scenes/s.json: render.integrator: unknown integrator 'magic' (choose one of: path, path-bsdf, ao, "
              "normals, depth, albedo, heatmap)");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("render": {"light_sampler": "tree"})")),
              "scenes/s.json: render.light_sampler: unknown light sampler 'tree' (choose one of: auto, power, bvh)");
    EXPECT_NE(parse_error(scene_with(kPlane, R"("render": {"russian_roulette": "sometimes"})"))
                  .find("scenes/s.json: render.russian_roulette: unknown Russian roulette rule 'sometimes'"),
              std::string::npos);
    EXPECT_EQ(parse_error(scene_with(R"({"type": "icosphere", "material": "white", "subdivisions": 11})")),
              "scenes/s.json: objects[0].subdivisions: 11 is out of range (must be in [0, 10])");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "plane", "material": "white", "size": [1, -1]})")),
              "scenes/s.json: objects[0].size[1]: -1 is out of range (must be > 0)");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("lights": [{"type": "spot", "position": [0,0,0], "direction": [0,-1,0], "intensity": 1, "inner_angle": 50, "outer_angle": 40}])")),
              "scenes/s.json: lights[0].inner_angle: must not exceed outer_angle (40.000000)");
    EXPECT_EQ(parse_error(scene_with(kPlane, R"("lights": [{"type": "directional", "direction": [0,0,0], "intensity": 1}])")),
              "scenes/s.json: lights[0].direction: a direction must not be zero");
}

TEST(SceneFileBad, MissingReferences) {
    EXPECT_EQ(parse_error(scene_with(R"({"type": "plane", "material": "chrome"})")),
              "scenes/s.json: objects[0].material: no material named 'chrome' (defined: white, lamp)");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "mesh", "file": "meshes/missing.obj"})")),
              "scenes/s.json: objects[0].file: scenes/meshes/missing.obj: no such file");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "plane"})")), "scenes/s.json: objects[0].material: required field is missing");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "cone", "material": "white"})")),
              "scenes/s.json: objects[0].type: unknown object type 'cone' (choose one of: plane, box, icosphere, "
              "sphere, grid, mesh)");
}

TEST(SceneFileBad, EmptyScenes) {
    EXPECT_EQ(parse_error(scene_with("")), "scenes/s.json: objects: the scene is empty: it needs at least one object");
    EXPECT_EQ(parse_error(std::string("{") + kCamera + "}"),
              "scenes/s.json: objects: required field is missing (a scene needs at least one object)");
    EXPECT_EQ(parse_error(R"({"objects": []})"), "scenes/s.json: camera: required field is missing");
    EXPECT_EQ(parse_error(scene_with(R"({"type": "plane", "material": "white", "transform": {"scale": 0}})")),
              "scenes/s.json: objects: the scene has no triangles left: all 2 were degenerate");
}

TEST(SceneFileBad, TooManyTriangles) {
    MemoryFiles files;
    LoadOptions o = files.options();
    o.max_triangles = 1000;
    const std::string msg = error_of([&] {
        parse_scene_file(scene_with(R"({"type": "sphere", "material": "white", "triangles": 5000})"), "s.json", o);
    });
    EXPECT_EQ(msg, "s.json: objects[0].triangles: 5000 is out of range (must be in [12, 1000])");
    // Refused before it is generated.
    EXPECT_EQ(error_of([&] {
                  parse_scene_file(scene_with(R"({"type": "icosphere", "material": "white", "subdivisions": 10})"),
                                   "s.json", o);
              }),
              "s.json: objects[0]: 20971520 more triangles would exceed the limit of 1000 for one scene");
}

// --- load_scene: what a user names ---------------------------------------------

TEST(LoadScene, DispatchesOnWhatItIsGiven) {
    EXPECT_EQ(load_scene("cornell").triangle_count(), 196u);
    EXPECT_EQ(error_of([] { load_scene("no/such/scene.json"); }), "no/such/scene.json: no such file");
    EXPECT_EQ(error_of([] { load_scene("no/such/mesh.obj"); }), "no/such/mesh.obj: no such file");
    EXPECT_EQ(error_of([] { load_scene("/"); }), "/: is a folder, not a scene file");
    EXPECT_NE(error_of([] { load_scene("nonesuch"); }).find("no built-in scene named 'nonesuch'"), std::string::npos);
    EXPECT_NE(error_of([] { load_scene(__FILE__); }).find("unknown scene file type '.cpp'"), std::string::npos);
    EXPECT_NE(error_of([] { load_scene("scaling:lots"); }).find("scaling:N"), std::string::npos);
    EXPECT_NE(error_of([] { load_scene("scaling:10"); }).find("[100, 50000000]"), std::string::npos);
}

TEST(LoadScene, FolderInsteadOfFile) {
    const std::string dir = test::temp_path("scene-folder.json");
    std::filesystem::create_directories(dir);
    EXPECT_EQ(error_of([&] { load_scene(dir); }), dir + ": is a folder, not a file");
    std::filesystem::remove(dir);
}

TEST(LoadScene, BareObjIsFramedAndLit) {
    MemoryFiles files;
    files.files["m.obj"] = "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n";
    const Scene s = load_scene("m.obj", files.options());
    EXPECT_EQ(s.triangle_count(), 1u + 2u);  // and the presentation's ground
    EXPECT_EQ(s.material_names[0], "(default)");
    EXPECT_TRUE(s.environment.emits());  // nothing in it emits: a sky and a sun
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.camera.target, glm::vec3(1, 1, 0));
    EXPECT_GT(s.camera.eye.z, 0.0f);  // the triangle faces +z, and is seen from there
    EXPECT_NO_THROW(camera_data(s.camera));
}

}  // namespace
}  // namespace clpath
