#include "render/surface_buffers.hpp"

#include <cstring>

#include "util/error.hpp"

namespace clpath {
namespace {
std::uint32_t stride_of(std::uint32_t flags) {
    return ((flags & CLP_SCENE_UVS) ? 6u : 0u) + ((flags & CLP_SCENE_TANGENTS) ? 12u : 0u) +
           ((flags & CLP_SCENE_COLORS) ? 12u : 0u);
}
// The records of `triangles` triangles in the layout `flags` names, from
// attributes each empty (the default then: no uv, a tangent to derive, white)
// or three per triangle.
void append_attributes(std::vector<float>& out, std::uint32_t flags, std::size_t triangles,
                       const std::vector<glm::vec2>& uvs, const std::vector<glm::vec4>& tangents,
                       const std::vector<glm::vec4>& colors) {
    for (std::size_t t = 0; t < triangles; ++t) {
        if (flags & CLP_SCENE_UVS)
            for (std::size_t c = 3 * t; c < 3 * t + 3; ++c) {
                const glm::vec2 v = uvs.empty() ? glm::vec2(0) : uvs[c];
                out.insert(out.end(), {v.x, v.y});
            }
        if (flags & CLP_SCENE_TANGENTS)
            for (std::size_t c = 3 * t; c < 3 * t + 3; ++c) {
                const glm::vec4 v = tangents.empty() ? glm::vec4(0) : tangents[c];
                out.insert(out.end(), {v.x, v.y, v.z, v.w});
            }
        if (flags & CLP_SCENE_COLORS)
            for (std::size_t c = 3 * t; c < 3 * t + 3; ++c) {
                const glm::vec4 v = colors.empty() ? glm::vec4(1) : colors[c];
                out.insert(out.end(), {v.x, v.y, v.z, v.w});
            }
    }
}
std::size_t texel_words(const Texture& t) {
    return std::size_t(t.width) * std::size_t(t.height) * (t.is_float ? 4 : 1);
}
}  // namespace

SurfaceBuffers pack_surface_buffers(const Scene& s) {
    SurfaceBuffers b;
    b.scene_flags = s.attribute_flags();
    b.attr_stride = stride_of(b.scene_flags);
    if (b.attr_stride > 0) {
        std::size_t triangles = s.triangle_count();
        for (const auto& m : s.meshes) triangles += m.triangle_count();
        b.attrs.reserve(triangles * b.attr_stride);
        append_attributes(b.attrs, b.scene_flags, s.triangle_count(), s.uvs, s.tangents, s.colors);
        for (const auto& m : s.meshes)
            append_attributes(b.attrs, b.scene_flags, m.triangle_count(), m.uvs, m.tangents, m.colors);
    }
    std::size_t words = 0;
    for (const auto& t : s.textures) words += texel_words(t);
    if (words > 0xffffffffull) throw Error("the scene's textures exceed 16 GiB, more than one texel buffer addresses");
    b.texels.reserve(words);
    for (const auto& t : s.textures) {
        TextureDesc d{};
        d.offset = std::uint32_t(b.texels.size());
        d.width = std::uint32_t(t.width);
        d.height = std::uint32_t(t.height);
        d.flags = (t.wrap_s << CLP_TEXF_WRAP_S_SHIFT) | (t.wrap_t << CLP_TEXF_WRAP_T_SHIFT) |
                  (t.is_float ? CLP_TEXF_FLOAT : 0u) | (t.nearest ? CLP_TEXF_NEAREST : 0u);
        if (t.is_float) {
            const std::size_t at = b.texels.size();
            b.texels.resize(at + t.rgba32.size());
            std::memcpy(b.texels.data() + at, t.rgba32.data(), t.rgba32.size() * sizeof(float));
        } else {
            for (std::size_t i = 0; i + 3 < t.rgba8.size(); i += 4)
                b.texels.push_back(std::uint32_t(t.rgba8[i]) | std::uint32_t(t.rgba8[i + 1]) << 8 |
                                   std::uint32_t(t.rgba8[i + 2]) << 16 | std::uint32_t(t.rgba8[i + 3]) << 24);
        }
        b.textures.push_back(d);
    }
    return b;
}

}  // namespace clpath
