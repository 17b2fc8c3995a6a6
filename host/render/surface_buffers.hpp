#pragma once
// What the kernels read about surfaces beyond positions and normals, packed
// for upload: per-triangle vertex attributes (texture coordinates, tangents,
// colours; kernels/textures.cl reads the layout from FrameParams) and every
// texture in one texel buffer with a descriptor each.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

struct SurfaceBuffers {
    std::vector<float> attrs;      // attr_stride floats per triangle: the flat ones, then each instanced mesh's
    std::uint32_t attr_stride = 0;
    std::uint32_t scene_flags = 0;  // CLP_SCENE_UVS, _TANGENTS, _COLORS
    std::vector<TextureDesc> textures;
    std::vector<std::uint32_t> texels;
};

// Throws clpath::Error when the textures exceed what 32-bit texel offsets address.
SurfaceBuffers pack_surface_buffers(const Scene& scene);

}  // namespace clpath
