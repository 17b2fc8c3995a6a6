// glTF files clpath does not read are refused by what they are (glTF 1.0, a
// required extension clpath does not implement), not by whatever breaks
// first; a triangle list with an incomplete last triangle loads without it,
// as in assimp. Each refusal has a control that loads.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_scene.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {


bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A glTF 1.0 document: objects in dictionaries by id, a buffer by URI.
json version_1_doc() {
    return json::parse(R"({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA", "byteLength": 36}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": 36}},
        "accessors": {"p": {"bufferView": "v", "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "mode": 4}]}},
        "nodes": {"n": {"meshes": ["m"]}},
        "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s"})");
}

TEST(GltfSupport, Version1IsRefusedByName) {
    const std::string want = "v1.gltf: glTF 1.0 is not supported (glTF 2.0 is)";
    json doc = version_1_doc();
    EXPECT_TRUE(has(gltf_text_error("v1.gltf", doc.dump()), want)) << gltf_text_error("v1.gltf", doc.dump());
    // Some exporters wrote the version as a number (tinygltf then refuses the asset).
    doc["asset"]["version"] = 1;
    EXPECT_TRUE(has(gltf_text_error("v1.gltf", doc.dump()), want)) << gltf_text_error("v1.gltf", doc.dump());
    // Without an asset, by its dictionaries.
    doc.erase("asset");
    EXPECT_TRUE(has(gltf_text_error("v1.gltf", doc.dump()), want)) << gltf_text_error("v1.gltf", doc.dump());
    // Binary glTF 1.0 (KHR_binary_glTF): header version 1.
    const std::string body = version_1_doc().dump();
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb = "glTF" + u32(1) + u32(std::uint32_t(20 + body.size())) + u32(std::uint32_t(body.size())) +
                            u32(0) + body;
    EXPECT_TRUE(has(gltf_text_error("v1.glb", glb), "v1.glb: glTF 1.0 is not supported (glTF 2.0 is)")) << gltf_text_error("v1.glb", glb);
    // Control: a glTF 2.0 file, with and without the binary container, loads.
    EXPECT_EQ(gltf_text_scene("q.gltf", quad_model().embedded()).triangle_count(), 2u);
    EXPECT_EQ(gltf_text_scene("q.glb", quad_model().glb()).triangle_count(), 2u);
}

TEST(GltfSupport, UnsupportedRequiredExtensionsAreNamed) {
    // Data that tinygltf reads but that means something else without the
    // extension. (Draco and meshopt compression are read: gltf_compressed_test.)
    for (const char* ext : {"KHR_texture_basisu", "EXT_texture_webp"}) {
        GltfBuilder g = quad_model();
        g.doc["extensionsUsed"] = {ext};
        g.doc["extensionsRequired"] = {ext};
        const std::string e = gltf_text_error("x.gltf", g.embedded());
        EXPECT_TRUE(has(e, std::string("x.gltf: extensionsRequired: ") + ext + " is not supported")) << e;
        // The message lists what clpath implements, the compressed meshes among them.
        EXPECT_TRUE(has(e, "(clpath implements EXT_meshopt_compression, KHR_draco_mesh_compression, ")) << e;
    }
    GltfBuilder two = quad_model();
    two.doc["extensionsRequired"] = {"KHR_lights_punctual", "KHR_texture_basisu", "EXT_texture_webp"};
    const std::string e = gltf_text_error("two.gltf", two.embedded());
    EXPECT_TRUE(has(e, "two.gltf: extensionsRequired: KHR_texture_basisu, EXT_texture_webp are not supported")) << e;
    // Controls: a required extension clpath implements, and an unsupported
    // one that is only used (optional), load.
    GltfBuilder ok = quad_model();
    ok.doc["extensionsUsed"] = {"KHR_materials_ior", "KHR_texture_basisu"};
    ok.doc["extensionsRequired"] = {"KHR_materials_ior"};
    const Scene loaded = gltf_text_scene("ok.gltf", ok.embedded());
    EXPECT_EQ(loaded.triangle_count(), 2u);
    EXPECT_TRUE(loaded.warnings.empty());
    // A required extension that only changes how materials look (as in
    // assimp's BoxTextured-glTF-techniqueWebGL) loads, with a warning naming it.
    ok.doc["extensionsRequired"] = {"KHR_materials_ior", "KHR_technique_webgl"};
    const Scene look = gltf_text_scene("ok.gltf", ok.embedded());
    EXPECT_EQ(look.triangle_count(), 2u);
    ASSERT_EQ(look.warnings.size(), 1u);
    EXPECT_TRUE(has(look.warnings[0], "ok.gltf: extensionsRequired: KHR_technique_webgl is not implemented; rendered with"))
        << look.warnings[0];
}

TEST(GltfSupport, IncompleteLastTriangleIsDroppedWithAWarning) {
    // Unindexed: 8 vertices, 2 whole triangles and 2 vertices left over.
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0}, "VEC3", 3);
    g.doc["meshes"] = json::array({json{{"primitives", json::array({json{{"attributes", {{"POSITION", pos}}}}})}}});
    g.doc["nodes"] = json::array({json{{"mesh", 0}}});
    const Scene s = gltf_text_scene("c.gltf", g.embedded());
    EXPECT_EQ(s.triangle_count(), 2u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.warnings[0], "c.gltf: meshes[0].primitives[0]: 8 corners are not a whole number of triangles; "
                             "the last 2 are dropped");
    // Indexed, the same: 4 indices are one triangle and one corner left over.
    const int idx = g.indices({0, 1, 2, 3});
    g.doc["meshes"][0]["primitives"][0]["indices"] = idx;
    const Scene t = gltf_text_scene("c.gltf", g.embedded());
    EXPECT_EQ(t.triangle_count(), 1u);
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_EQ(t.warnings[0], "c.gltf: meshes[0].primitives[0]: 4 corners are not a whole number of triangles; the last 1 is dropped");
    // Control: a whole list loads with no warning.
    g.doc["meshes"][0]["primitives"][0]["indices"] = g.indices({0, 1, 2, 3, 4, 5});
    EXPECT_TRUE(gltf_text_scene("c.gltf", g.embedded()).warnings.empty());
    // An index out of range stays an error, even in the dropped corners.
    const int far = g.indices({0, 1, 2, 8});
    g.doc["meshes"][0]["primitives"][0]["indices"] = far;
    EXPECT_TRUE(has(gltf_text_error("c.gltf", g.embedded()), "c.gltf: meshes[0].primitives[0].indices: index 8 at position 3 is out of range"));
}

// Points and lines among triangles are skipped with a warning, as an OBJ's
// are (assimp's IncorrectVertexArrays/Cube.gltf has both); a file of nothing
// else is refused, naming them.
TEST(GltfSupport, PointsAndLinesAmongTrianglesAreSkipped) {
    GltfBuilder g = quad_model();
    json lines = g.doc["meshes"][0]["primitives"][0];
    lines["mode"] = 1;
    g.doc["meshes"][0]["primitives"].push_back(lines);
    const Scene s = gltf_text_scene("m.gltf", g.embedded());
    EXPECT_EQ(s.triangle_count(), 2u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.warnings[0], "m.gltf: meshes[0].primitives[1].mode: points and lines cannot be rendered (clpath "
                             "renders triangles); skipped");
    g.doc["meshes"][0]["primitives"].erase(0);
    const std::string e = gltf_text_error("m.gltf", g.embedded());
    EXPECT_TRUE(has(e, "m.gltf: the file places no triangles (an empty scene); m.gltf: meshes[0].primitives[0].mode: "
                       "points and lines cannot be rendered")) << e;
}

}  // namespace
