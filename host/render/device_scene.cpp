#include "render/device_scene.hpp"

#include <algorithm>

#include "render/kernel_programs.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// Kernels take no empty buffers: a missing part gets one zero record.
std::size_t normal_bytes(const PreparedScene& s) { return std::max<std::size_t>(16, s.normals.size() * 12); }
std::size_t light_bytes(const PreparedScene& s) { return std::max<std::size_t>(1, s.lights.size()) * sizeof(Light); }
// One zero record when no kernel reads them (no textures, no alpha).
std::size_t material_ext_bytes(const PreparedScene& s) {
    return std::max<std::size_t>(1, s.material_ext.size()) * sizeof(MaterialExt);
}
std::size_t alias_bytes(const PreparedScene& s) {
    return std::max<std::size_t>(1, s.light_alias.size()) * sizeof(AliasEntry);
}
// The light BVH: nodes, a 64-bit trail per light, the infinite lights' indices.
std::size_t light_bvh_node_bytes(const PreparedScene& s) {
    return std::max<std::size_t>(1, s.light_bvh.nodes.size()) * sizeof(LightBvhNode);
}
std::size_t light_trail_bytes(const PreparedScene& s) {
    return std::max<std::size_t>(1, s.light_bvh.trail.size()) * sizeof(std::uint64_t);
}
std::size_t light_infinite_bytes(const PreparedScene& s) {
    return std::max<std::size_t>(1, s.light_bvh.infinite.size()) * sizeof(std::uint32_t);
}

}  // namespace

NodeLayout DeviceScene::device_node_layout(const DeviceInfo& device, const PreparedScene& s) {
    return node_layout(kernel_code(device), s.summary.instanced);
}

std::vector<std::pair<std::string, std::size_t>> DeviceScene::memory_needs(const PreparedScene& s, NodeLayout layout) {
    // The kernels' node records (device_nodes): widened from the binary tree, so sized by converting.
    return memory_needs(s, scene_node_bytes(s, layout).size());
}

std::vector<std::pair<std::string, std::size_t>> DeviceScene::memory_needs(const PreparedScene& s,
                                                                           std::size_t node_bytes) {
    return {{"BVH nodes", node_bytes},
            {"triangles", s.accel.triangles.size() * sizeof(TriVerts)},
            {"triangle materials", s.triangle_material.size() * sizeof(std::uint32_t)},
            {"materials", s.materials.size() * sizeof(Material)},
            {"material extensions", material_ext_bytes(s)},
            {"shading normals", normal_bytes(s)},
            {"lights", light_bytes(s) + alias_bytes(s)},
            {"light BVH", light_bvh_node_bytes(s) + light_trail_bytes(s) + light_infinite_bytes(s)},
            {"environment image", s.environment.pixels.size() * sizeof(float)},
            {"environment distribution", s.environment.cdf.size() * sizeof(float)},
            {"surface attributes", std::max<std::size_t>(16, s.surface.attrs.size() * sizeof(float))},
            {"textures", std::max<std::size_t>(16, s.surface.textures.size() * sizeof(TextureDesc)) +
                             std::max<std::size_t>(16, s.surface.texels.size() * sizeof(std::uint32_t))}};
}

const std::vector<std::string>& scene_buffer_names() {
#define CLP_SCENE_BUFFER_TEXT(type, name) #name,
    static const std::vector<std::string> names{CLP_SCENE_BUFFERS(CLP_SCENE_BUFFER_TEXT)};
#undef CLP_SCENE_BUFFER_TEXT
    return names;
}

std::size_t DeviceScene::bytes() const {
    std::size_t n = 0;
    for (const Buffer& b : buffers_) n += b.bytes();
    return n;
}

DeviceScene::DeviceScene(Context& ctx, const PreparedScene& s, const std::vector<unsigned char>& node_bytes)
    : ctx_(ctx), summary_(s.summary) {
    ctx.check_fits(memory_needs(s, node_bytes.size()));
    slot(SceneBuffer::nodes) = ctx.buffer(node_bytes.size(), CL_MEM_READ_ONLY, "BVH nodes", node_bytes.data());
    slot(SceneBuffer::tris) = ctx.buffer(s.accel.triangles.size() * sizeof(TriVerts), CL_MEM_READ_ONLY, "triangles",
                       s.accel.triangles.data());
    slot(SceneBuffer::tri_material) = ctx.buffer(s.triangle_material.size() * sizeof(std::uint32_t), CL_MEM_READ_ONLY,
                               "triangle materials", s.triangle_material.data());
    slot(SceneBuffer::materials) =
        ctx.buffer(s.materials.size() * sizeof(Material), CL_MEM_READ_ONLY, "materials", s.materials.data());
    const MaterialExt no_ext{};
    slot(SceneBuffer::material_ext) = ctx.buffer(material_ext_bytes(s), CL_MEM_READ_ONLY, "material extensions",
                               s.material_ext.empty() ? static_cast<const void*>(&no_ext) : s.material_ext.data());
    const std::vector<float> zeros(16, 0.0f);
    slot(SceneBuffer::normals) = ctx.buffer(normal_bytes(s), CL_MEM_READ_ONLY, "shading normals",
                          s.normals.empty() ? static_cast<const void*>(zeros.data()) : s.normals.data());
    const Light no_light{};
    const AliasEntry no_alias{};
    slot(SceneBuffer::lights) = ctx.buffer(light_bytes(s), CL_MEM_READ_ONLY, "lights",
                         s.lights.empty() ? static_cast<const void*>(&no_light) : s.lights.data());
    slot(SceneBuffer::alias) = ctx.buffer(alias_bytes(s), CL_MEM_READ_ONLY, "light alias table",
                        s.light_alias.empty() ? static_cast<const void*>(&no_alias) : s.light_alias.data());
    // The trails as the kernels read them (uint2: low word first), from the
    // host's 64-bit integers, whatever the host's byte order.
    std::vector<std::uint32_t> trails(2 * std::max<std::size_t>(1, s.light_bvh.trail.size()), 0u);
    for (std::size_t i = 0; i < s.light_bvh.trail.size(); ++i) {
        trails[2 * i] = std::uint32_t(s.light_bvh.trail[i]);
        trails[2 * i + 1] = std::uint32_t(s.light_bvh.trail[i] >> 32);
    }
    const LightBvhNode no_node{};
    const std::uint32_t no_infinite = CLP_NO_LIGHT;
    slot(SceneBuffer::light_bvh) =
        ctx.buffer(light_bvh_node_bytes(s), CL_MEM_READ_ONLY, "light BVH nodes",
                   s.light_bvh.nodes.empty() ? static_cast<const void*>(&no_node) : s.light_bvh.nodes.data());
    slot(SceneBuffer::light_trails) = ctx.buffer(light_trail_bytes(s), CL_MEM_READ_ONLY, "light BVH trails", trails.data());
    slot(SceneBuffer::light_infinite) =
        ctx.buffer(light_infinite_bytes(s), CL_MEM_READ_ONLY, "infinite lights",
                   s.light_bvh.infinite.empty() ? static_cast<const void*>(&no_infinite) : s.light_bvh.infinite.data());
    slot(SceneBuffer::env_pixels) = ctx.buffer(s.environment.pixels.size() * sizeof(float), CL_MEM_READ_ONLY, "environment image",
                             s.environment.pixels.data());
    slot(SceneBuffer::env_cdf) = ctx.buffer(s.environment.cdf.size() * sizeof(float), CL_MEM_READ_ONLY, "environment distribution",
                          s.environment.cdf.data());
    // Texture coordinates, tangents, colours and textures: a 16-byte stand-in when the scene has none.
    auto upload = [&](std::size_t bytes, const void* data, const char* what) {
        return bytes ? ctx.buffer(bytes, CL_MEM_READ_ONLY, what, data)
                     : ctx.buffer(16, CL_MEM_READ_ONLY, what, zeros.data());
    };
    const SurfaceBuffers& sb = s.surface;
    slot(SceneBuffer::attrs) = upload(sb.attrs.size() * sizeof(float), sb.attrs.data(), "surface attributes");
    slot(SceneBuffer::tex_desc) = upload(sb.textures.size() * sizeof(TextureDesc), sb.textures.data(), "texture descriptors");
    slot(SceneBuffer::texels) = upload(sb.texels.size() * sizeof(std::uint32_t), sb.texels.data(), "texels");
    for (std::size_t i = 0; i < buffers_.size(); ++i)
        if (!buffers_[i].get()) throw Error("internal: the scene buffer '" + scene_buffer_names()[i] + "' was not uploaded");
}

void DeviceScene::bind(Kernel& k, cl_uint first) const {
    for (cl_uint i = 0; i < kArgCount; ++i) k.arg(first + i, buffers_[i]);
}

}  // namespace clpath
