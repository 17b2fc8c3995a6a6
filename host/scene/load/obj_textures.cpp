#include "scene/load/obj_textures.hpp"

#include <algorithm>

#include "util/error.hpp"

namespace clpath {
namespace {
TextureImage load(const std::string& path, const std::string& material, const LoadOptions& options) {
    std::string bytes;
    try {
        bytes = options.read_file(path);
    } catch (const Error& e) {
        throw Error("material '" + material + "': " + e.what());
    }
    TextureImage t = options.decode_texture(bytes, path);
    if (t.is_float) {
        // Colour maps are 8-bit in practice; a float one is quantised to keep one texel format here.
        t.rgba8.resize(t.rgba32.size());
        for (std::size_t i = 0; i < t.rgba32.size(); ++i)
            t.rgba8[i] = std::uint8_t(std::clamp(t.rgba32[i], 0.0f, 1.0f) * 255.0f + 0.5f);
        t.rgba32.clear();
        t.is_float = false;
    }
    return t;
}
}  // namespace

SceneMaterial obj_material_with_textures(Scene& scene, const ObjMaterial& om, const LoadOptions& options) {
    SceneMaterial m = om.material;
    if (om.diffuse_texture.empty() && om.alpha_texture.empty()) return m;
    TextureImage base;
    if (!om.diffuse_texture.empty()) base = load(om.diffuse_texture, om.name, options);
    if (!om.alpha_texture.empty() && om.alpha_texture != om.diffuse_texture) {
        const TextureImage a = load(om.alpha_texture, om.name, options);
        if (om.diffuse_texture.empty()) {
            base = a;
            for (std::size_t i = 0; i + 3 < base.rgba8.size(); i += 4) base.rgba8[i] = base.rgba8[i + 1] = base.rgba8[i + 2] = 255;
        } else if (a.width != base.width || a.height != base.height) {
            throw Error(om.alpha_texture + ": map_d of material '" + om.name + "' is " + std::to_string(a.width) + "x" +
                        std::to_string(a.height) + ", but its map_Kd is " + std::to_string(base.width) + "x" +
                        std::to_string(base.height) + " (clpath needs them the same size)");
        }
        // map_d is a coverage mask: its first channel becomes alpha.
        for (std::size_t i = 0; i + 3 < base.rgba8.size(); i += 4) base.rgba8[i + 3] = a.rgba8[i];
    }
    Texture t;
    t.name = om.diffuse_texture.empty() ? om.alpha_texture : om.diffuse_texture;
    t.width = base.width;
    t.height = base.height;
    t.rgba8 = std::move(base.rgba8);
    scene.textures.push_back(std::move(t));
    m.texture[CLP_TEX_BASE] = int(scene.textures.size() - 1);
    return m;
}

}  // namespace clpath
