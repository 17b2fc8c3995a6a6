// glTF nodes that place the same mesh (scene/load/gltf_scene.cpp): stored
// once and placed by instances, with its vertex attributes, unless it emits
// (then flattened); the bare model's presentation measures every copy.
#include <gtest/gtest.h>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_scene.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {

// The unit quad placed by three nodes: as is, moved along x, and moved and
// mirrored; one mesh the three share, or (shared false) three copies of it.
GltfBuilder three_quads(bool with_uvs, bool shared = true) {
    GltfBuilder g = quad_model();
    if (!with_uvs) g.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    const int b = shared ? 0 : 1, c = shared ? 0 : 2;
    if (!shared) g.doc["meshes"] = json::array({g.doc["meshes"][0], g.doc["meshes"][0], g.doc["meshes"][0]});
    g.doc["nodes"] = json::array({json{{"mesh", 0}}, json{{"mesh", b}, {"translation", {3, 0, 0}}},
                                  json{{"mesh", c}, {"translation", {6, 1, 0}}, {"scale", {-1, 2, 1}}}});
    g.doc["scenes"] = json::array({json{{"nodes", {0, 1, 2}}}});
    return g;
}

Scene presented(const std::string& text) {
    MemoryFiles f;
    f.files["q.gltf"] = text;
    return gltf_scene("q.gltf", f.options());
}

TEST(GltfInstances, AMeshPlacedBySeveralNodesIsStoredOnce) {
    const Scene s = gltf_text_scene("q.gltf", three_quads(false).embedded());
    EXPECT_EQ(s.triangle_count(), 0u);
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].triangle_count(), 2u);
    ASSERT_EQ(s.instances.size(), 3u);
    EXPECT_EQ(s.placed_triangle_count(), 6u);
    EXPECT_EQ(s.instances[1].object_to_world[3], glm::vec4(3, 0, 0, 1));
    EXPECT_EQ(s.instances[2].object_to_world[0], glm::vec4(-1, 0, 0, 0));
    // Flattened, the copies are the triangles the loader placed before
    // instancing: the same corners, the mirrored copy's front still +z.
    const Scene flat = flatten_instances(s);
    ASSERT_EQ(flat.triangle_count(), 6u);
    for (std::size_t t = 0; t < 6; ++t) {
        const glm::vec3 n = glm::cross(flat.vertices[3 * t + 1] - flat.vertices[3 * t], flat.vertices[3 * t + 2] - flat.vertices[3 * t]);
        EXPECT_GT(n.z, 0.0f) << "triangle " << t;
    }
}

TEST(GltfInstances, AMeshWithTextureCoordinatesIsInstancedWithThem) {
    const Scene s = gltf_text_scene("q.gltf", three_quads(true).embedded());
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 3u);
    EXPECT_EQ(s.meshes[0].uvs.size(), 6u);
    EXPECT_TRUE(s.uvs.empty());  // no flat triangle has any
    // Flattened, each copy has the coordinates the loader gives the same
    // quads placed by three meshes, corner by corner (the mirrored copy's
    // two corners swapped back with their coordinates).
    const Scene flat = flatten_instances(s);
    const Scene loaded = gltf_text_scene("q.gltf", three_quads(true, false).embedded());
    ASSERT_TRUE(loaded.instances.empty());
    ASSERT_EQ(flat.vertices.size(), loaded.vertices.size());
    ASSERT_EQ(flat.uvs.size(), loaded.uvs.size());
    for (std::size_t i = 0; i < flat.vertices.size(); ++i) {
        EXPECT_EQ(flat.vertices[i], loaded.vertices[i]) << i;
        EXPECT_EQ(flat.uvs[i], loaded.uvs[i]) << i;
    }
}

TEST(GltfInstances, AnEmissiveMeshIsPlacedFlattened) {
    GltfBuilder g = three_quads(false);
    g.doc["materials"] = json::array({json{{"emissiveFactor", {1, 1, 1}}}});
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const Scene s = gltf_text_scene("q.gltf", g.embedded());
    EXPECT_TRUE(s.meshes.empty());
    EXPECT_EQ(s.triangle_count(), 6u);
    bool noted = false;
    for (const auto& n : s.notes)
        noted = noted || n.find("q.gltf: 1 mesh primitives placed by several nodes are placed flattened, not instanced "
                                "(they emit") != std::string::npos;
    EXPECT_TRUE(noted);
}

// The presentation frames what is placed: the same camera for the
// instanced copies as for the same copies flattened.
TEST(GltfInstances, ThePresentationFramesEveryCopy) {
    const Scene inst = presented(three_quads(false).embedded());
    const Scene flat = presented(three_quads(false, false).embedded());
    ASSERT_FALSE(inst.instances.empty());
    ASSERT_TRUE(flat.instances.empty());
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(inst.camera.eye[k], flat.camera.eye[k], 1e-4f) << k;
        EXPECT_NEAR(inst.camera.target[k], flat.camera.target[k], 1e-4f) << k;
    }
    // Control: framing the first copy alone puts the camera elsewhere.
    GltfBuilder one = quad_model();
    one.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    const Scene single = presented(one.embedded());
    EXPECT_GT(glm::length(single.camera.target - inst.camera.target), 1.0f);
}

}  // namespace
