// clpath export --format embree: the OBJ, MTL and command script Embree's
// example path tracer reads hold the scene's mesh, materials, camera, image
// size, point lights and path length; what that tracer would render
// differently is refused. (tests/bench/path_tests.cmake runs Embree's own
// pathtracer on the script where embree-tools is installed.)
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <vector>

#include "scene/export/embree_export.hpp"
#include "scene/export/obj_export.hpp"
#include "scene/load/scene_loader.hpp"
#include "scene/memory_files.hpp"

namespace clpath {
namespace {

Scene bundled(const std::string& name) { return load_scene(test::scenes_dir() + "/" + name + ".json"); }

// The script's options, comments dropped: option -> its values as written.
std::map<std::string, std::vector<std::string>> options(const std::string& ecs) {
    std::map<std::string, std::vector<std::string>> m;
    std::istringstream in(ecs);
    std::string line, current;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string w;
        words >> current;
        std::vector<std::string>& values = m[current];
        if (!values.empty()) values.push_back("|");  // a repeated option
        while (words >> w) values.push_back(w);
    }
    return m;
}

TEST(EmbreeExport, PointLightCornellScript) {
    Scene s = bundled("cornell-point");
    s.render.max_depth = 4;
    const EmbreeExport e = export_embree_scene(s, "box", "test");
    const auto o = options(e.ecs);
    using V = std::vector<std::string>;
    EXPECT_EQ(o.at("-i"), V({"box.obj"}));
    EXPECT_EQ(o.at("--vp"), V({"278", "273", "-800"}));
    EXPECT_EQ(o.at("--vi"), V({"278", "273", "0"}));
    EXPECT_EQ(o.at("--vu"), V({"0", "1", "0"}));
    EXPECT_FLOAT_EQ(std::stof(o.at("--fov").at(0)), s.camera.vfov_degrees);
    EXPECT_EQ(o.at("--size"), V({"512", "512"}));
    ASSERT_EQ(o.at("--pointlight").size(), 6u);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(std::stof(o.at("--pointlight")[a]), s.lights[0].position[a]);  // %.9g: the same float
        EXPECT_EQ(std::stof(o.at("--pointlight")[3 + a]), s.lights[0].intensity[a]);
    }
    EXPECT_EQ(o.at("--spp"), V({std::to_string(s.render.spp)}));
    EXPECT_EQ(o.at("--max-path-length"), V({"4"}));
    // The mesh and materials are the OBJ export's, read back as the same triangles.
    const ObjMeshText mesh = obj_mesh_text(s, "box", "test");
    EXPECT_EQ(e.obj, mesh.obj);
    EXPECT_EQ(e.mtl, mesh.mtl);
    test::MemoryFiles files;
    files.files["/mem/box.obj"] = e.obj;
    files.files["/mem/box.mtl"] = e.mtl;
    const Scene back = load_scene("/mem/box.obj", files.options());
    ASSERT_GE(back.triangle_count(), s.triangle_count());
    for (std::size_t v = 0; v < s.vertices.size(); ++v) ASSERT_EQ(back.vertices[v], s.vertices[v]) << "vertex " << v;
}

TEST(EmbreeExport, OneLineForEachPointLight) {
    Scene s = bundled("cornell-point");
    PunctualLight second = s.lights[0];
    second.position.x = 100;
    s.lights.push_back(second);
    const auto o = options(export_embree_scene(s, "box", "test").ecs);
    ASSERT_EQ(o.at("--pointlight").size(), 13u);  // two of six values, with a separator
    EXPECT_EQ(o.at("--pointlight")[7], "100");
}

TEST(EmbreeExport, RefusesWhatEmbreesPathTracerRendersDifferently) {
    auto refusal = [](const Scene& s) { return test::error_of([&] { export_embree_scene(s, "x", "test"); }); };
    EXPECT_NE(refusal(bundled("cornell-classic")).find("emits light"), std::string::npos);
    Scene mirror = bundled("cornell-point");
    mirror.materials[mirror.triangle_material[0]].kind = CLP_MAT_MIRROR;
    EXPECT_NE(refusal(mirror).find("only diffuse surfaces"), std::string::npos);
    Scene spot = bundled("cornell-point");
    spot.lights[0].type = PunctualLight::Type::Spot;
    EXPECT_NE(refusal(spot).find("spot light"), std::string::npos);
    Scene dark = bundled("cornell-point");
    dark.lights.clear();
    EXPECT_NE(refusal(dark).find("no point light"), std::string::npos);
    Scene sky = bundled("cornell-point");
    sky.environment.color = glm::vec3(1.0f);
    EXPECT_NE(refusal(sky).find("environment"), std::string::npos);
    EXPECT_NO_THROW(export_embree_scene(bundled("cornell-point"), "x", "test"));  // the control
}

}  // namespace
}  // namespace clpath
