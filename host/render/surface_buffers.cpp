#include "render/surface_buffers.hpp"

#include <cstring>

#include "util/error.hpp"

namespace clpath {
namespace {
std::uint32_t stride_of(const Scene& s, std::uint32_t* flags) {
    std::uint32_t stride = 0, f = 0;
    if (!s.uvs.empty()) stride += 6, f |= CLP_SCENE_UVS;
    if (!s.tangents.empty()) stride += 12, f |= CLP_SCENE_TANGENTS;
    if (!s.colors.empty()) stride += 12, f |= CLP_SCENE_COLORS;
    if (flags) *flags = f;
    return stride;
}
std::size_t texel_words(const Texture& t) {
    return std::size_t(t.width) * std::size_t(t.height) * (t.is_float ? 4 : 1);
}
}  // namespace

SurfaceBuffers pack_surface_buffers(const Scene& s) {
    SurfaceBuffers b;
    b.attr_stride = stride_of(s, &b.scene_flags);
    b.attrs.reserve(s.triangle_count() * b.attr_stride);
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        if (!s.uvs.empty())
            for (int c = 0; c < 3; ++c) b.attrs.insert(b.attrs.end(), {s.uvs[3 * t + c].x, s.uvs[3 * t + c].y});
        if (!s.tangents.empty())
            for (int c = 0; c < 3; ++c) {
                const glm::vec4 v = s.tangents[3 * t + c];
                b.attrs.insert(b.attrs.end(), {v.x, v.y, v.z, v.w});
            }
        if (!s.colors.empty())
            for (int c = 0; c < 3; ++c) {
                const glm::vec4 v = s.colors[3 * t + c];
                b.attrs.insert(b.attrs.end(), {v.x, v.y, v.z, v.w});
            }
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
