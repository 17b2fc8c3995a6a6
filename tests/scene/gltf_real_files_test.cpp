// What real exporters write: gltfpack's quantised meshes (KHR_mesh_quantization
// with KHR_texture_transform), orthographic cameras, skins and morph targets
// in their rest pose, and missing image files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "memory_files.hpp"
#include "support/quantised_gltf.hpp"
#include "scene/load/gltf_model.hpp"
#include "scene/load/gltf_scene.hpp"

namespace clpath {
namespace {

using nlohmann::json;
using test::MemoryFiles;

bool has(const std::vector<std::string>& warnings, const std::string& part) {
    for (const auto& w : warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

// Bundled Suzanne quantised as gltfpack does by default (support/quantised_gltf.hpp).
TEST(GltfRealFiles, QuantisedSuzanneMatchesTheOriginalWithinItsSteps) {
    const LoadOptions disk;
    const GltfModel original = load_gltf(test::scenes_dir() + "/suzanne/Suzanne.gltf", disk);
    ASSERT_EQ(original.meshes.size(), 1u);
    const GltfPrimitive& p = original.meshes[0][0];
    const std::size_t n = p.vertices.size();
    const test::QuantisedGltf quantised = test::quantise_like_gltfpack(p, {"missing-on-purpose.png"}, "q.bin");
    const float step = quantised.step, extent = quantised.extent;
    const glm::vec2 uv_scale = quantised.uv_scale;
    MemoryFiles mem;
    mem.files["q/model.gltf"] = quantised.doc.dump();
    mem.files["q/q.bin"] = quantised.bin;
    const GltfModel q = load_gltf("q/model.gltf", mem.options());
    ASSERT_EQ(q.instances.size(), 1u);
    const GltfPrimitive& qp = q.meshes[0][0];
    ASSERT_EQ(qp.vertices.size(), n);
    ASSERT_EQ(qp.uvs.size(), n);
    // Rounding puts each value within half a step of the original; the float
    // arithmetic of the grid (values up to 65535 steps) adds a few ulps of the extent.
    const float pos_bound = 0.5f * step + 8 * extent * 1.2e-7f;
    const glm::vec2 uv_bound = 0.5f * uv_scale / 65535.0f + glm::vec2(4e-7f);
    float worst_pos = 0, worst_uv = 0, worst_n = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 w(q.instances[0].world * glm::vec4(qp.vertices[i], 1));
        const glm::vec3 d = glm::abs(w - p.vertices[i]);
        worst_pos = std::max({worst_pos, d.x, d.y, d.z});
        const glm::vec2 du = glm::abs(qp.uvs[i] - p.uvs[i]);
        worst_uv = std::max({worst_uv, du.x / uv_bound.x, du.y / uv_bound.y});
        worst_n = std::max(worst_n, glm::length(glm::normalize(qp.normals[i]) - glm::normalize(p.normals[i])));
    }
    EXPECT_LE(worst_pos, pos_bound);
    EXPECT_LE(worst_uv, 1.0f);
    // int8 normals: each component within 0.5/127 before renormalising.
    EXPECT_LE(worst_n, std::sqrt(3.0f) * 0.5f / 127.0f * 2);
    // Control: without the node's transform the grid values are far off.
    EXPECT_GT(glm::length(qp.vertices[0] - p.vertices[0]), 1.0f);
    // The missing image: a warning naming its uri and the path it resolved to.
    EXPECT_TRUE(has(q.warnings, "q/model.gltf: images[0].uri: q/missing-on-purpose.png: no such file"));
    EXPECT_EQ(q.materials[0].material.texture[CLP_TEX_BASE], CLP_NO_TEXTURE);
}

// One triangle, in a document the tests below add to.
json triangle_doc(std::string& bin) {
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    bin.assign(reinterpret_cast<const char*>(pos), sizeof pos);
    return {{"asset", {{"version", "2.0"}}},
            {"buffers", {{{"byteLength", bin.size()}, {"uri", "t.bin"}}}},
            {"bufferViews", {{{"buffer", 0}, {"byteLength", bin.size()}}}},
            {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"scenes", {{{"nodes", {0}}}}}};
}

TEST(GltfRealFiles, SkinWithoutInverseBindMatricesLoadsInItsRestPose) {
    std::string bin;
    json doc = triangle_doc(bin);
    doc["nodes"] = {{{"mesh", 0}, {"skin", 0}}, {{"name", "joint"}, {"translation", {5, 0, 0}}}};
    doc["scenes"][0]["nodes"] = {0, 1};
    doc["skins"] = {{{"joints", {1}}}};
    doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 0}}};
    MemoryFiles mem;
    mem.files["s/t.bin"] = bin;
    mem.files["s/skin.gltf"] = doc.dump();
    const GltfModel m = load_gltf("s/skin.gltf", mem.options());
    ASSERT_EQ(m.instances.size(), 1u);
    EXPECT_EQ(m.meshes[0][0].vertices[1], glm::vec3(1, 0, 0));  // the bind pose, the joint's move not applied
    int rest_pose_warnings = 0;
    for (const auto& w : m.warnings) rest_pose_warnings += w.find("rest pose") != std::string::npos;
    EXPECT_EQ(rest_pose_warnings, 1);
    EXPECT_TRUE(has(m.warnings, "s/skin.gltf: 1 skin, 1 primitive with morph targets: not evaluated"));
    // Control: the same file without skins or targets loads without the warning.
    doc.erase("skins");
    doc["nodes"][0].erase("skin");
    doc["meshes"][0]["primitives"][0].erase("targets");
    mem.files["s/skin.gltf"] = doc.dump();
    EXPECT_FALSE(has(load_gltf("s/skin.gltf", mem.options()).warnings, "rest pose"));
}

TEST(GltfRealFiles, OrthographicCameraIsKept) {
    std::string bin;
    json doc = triangle_doc(bin);
    doc["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}};
    doc["nodes"].push_back({{"camera", 0}, {"translation", {0.25, 0.25, 3}}});
    doc["scenes"][0]["nodes"] = {0, 1};
    MemoryFiles mem;
    mem.files["o/t.bin"] = bin;
    mem.files["o/ortho.gltf"] = doc.dump();
    const GltfModel m = load_gltf("o/ortho.gltf", mem.options());
    ASSERT_TRUE(m.camera.has_value());
    EXPECT_EQ(m.camera->ortho_half_height, 1.0f);
    EXPECT_EQ(m.camera->width, 640);
    EXPECT_EQ(m.camera->height, 320);  // xmag / ymag = 2
    const CameraData d = camera_data(*m.camera);
    EXPECT_EQ(d.orthographic, 1u);
    EXPECT_NEAR(glm::length(glm::vec3(d.up[0], d.up[1], d.up[2])), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(d.right[0], d.right[1], d.right[2])), 2.0f, 1e-6f);
    // Control: a perspective camera's basis is scaled by tan(yfov / 2).
    doc["cameras"][0] = {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}};
    mem.files["o/ortho.gltf"] = doc.dump();
    const CameraData p = camera_data(*load_gltf("o/ortho.gltf", mem.options()).camera);
    EXPECT_EQ(p.orthographic, 0u);
    EXPECT_NEAR(glm::length(glm::vec3(p.up[0], p.up[1], p.up[2])), std::tan(0.25f), 1e-6f);
}

}  // namespace
}  // namespace clpath
