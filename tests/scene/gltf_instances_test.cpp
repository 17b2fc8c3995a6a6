// glTF nodes that place the same mesh (scene/load/gltf_scene.cpp): stored
// once and placed by instances where the mesh can be instanced, flattened
// where it cannot; the bare model's presentation measures every copy.
#include <gtest/gtest.h>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_scene.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {

// The unit quad placed by three nodes: as is, moved along x, and moved and mirrored.
GltfBuilder three_quads(bool with_uvs) {
    GltfBuilder g = quad_model();
    if (!with_uvs) g.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    g.doc["nodes"] = json::array({json{{"mesh", 0}}, json{{"mesh", 0}, {"translation", {3, 0, 0}}},
                                  json{{"mesh", 0}, {"translation", {6, 1, 0}}, {"scale", {-1, 2, 1}}}});
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

TEST(GltfInstances, AMeshWithTextureCoordinatesIsPlacedFlattened) {
    const Scene s = gltf_text_scene("q.gltf", three_quads(true).embedded());
    EXPECT_TRUE(s.meshes.empty());
    EXPECT_TRUE(s.instances.empty());
    EXPECT_EQ(s.triangle_count(), 6u);
    bool noted = false;
    for (const auto& n : s.notes) noted = noted || n.find("q.gltf: 1 mesh primitives placed by several nodes are placed flattened, not instanced") != std::string::npos;
    EXPECT_TRUE(noted);
}

// The presentation frames what is placed: the same camera for the
// instanced copies as for the same copies flattened.
TEST(GltfInstances, ThePresentationFramesEveryCopy) {
    const Scene inst = presented(three_quads(false).embedded());
    const Scene flat = presented(three_quads(true).embedded());
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
