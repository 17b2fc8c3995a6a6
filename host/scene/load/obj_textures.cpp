#include "scene/load/obj_textures.hpp"

#include <algorithm>
#include <optional>

#include "util/error.hpp"

namespace clpath {
namespace {
// A map whose file is missing or unreadable: as Blender does, the material
// loads without it (a neutral, white map), with a warning naming the .mtl
// line and the path the map resolved to. A file that is there but is not an
// image stays an error.
std::optional<TextureImage> load(Scene& scene, const ObjMaterial& om, const std::string& path, const char* keyword,
                                 int line, const LoadOptions& options) {
    std::string bytes;
    try {
        bytes = options.read_file(path);
    } catch (const RestrictedFileError&) {
        throw;
    } catch (const Error& e) {
        scene.warnings.push_back(om.mtl_file + ":" + std::to_string(line) + ": " + keyword + " of material '" + om.name +
                                 "': " + e.what() + "; the material is rendered without it");
        return std::nullopt;
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
    std::optional<TextureImage> base, alpha;
    if (!om.diffuse_texture.empty()) base = load(scene, om, om.diffuse_texture, "map_Kd", om.diffuse_texture_line, options);
    const bool own_alpha = !om.alpha_texture.empty() && om.alpha_texture != om.diffuse_texture;
    if (own_alpha) alpha = load(scene, om, om.alpha_texture, "map_d", om.alpha_texture_line, options);
    // map_d's file missing (or the map_Kd it shares): no mask to cut with.
    if (!om.alpha_texture.empty() && !(own_alpha ? alpha.has_value() : base.has_value())) m.alpha_mode = CLP_ALPHA_OPAQUE;
    if (!base && !alpha) return m;
    const bool from_diffuse = base.has_value();
    if (!base) {
        base = *alpha;
        for (std::size_t i = 0; i + 3 < base->rgba8.size(); i += 4) base->rgba8[i] = base->rgba8[i + 1] = base->rgba8[i + 2] = 255;
    } else if (alpha && (alpha->width != base->width || alpha->height != base->height)) {
        throw Error(om.alpha_texture + ": map_d of material '" + om.name + "' is " + std::to_string(alpha->width) + "x" +
                    std::to_string(alpha->height) + ", but its map_Kd is " + std::to_string(base->width) + "x" +
                    std::to_string(base->height) + " (clpath needs them the same size)");
    }
    // map_d is a coverage mask: its first channel becomes alpha.
    if (alpha)
        for (std::size_t i = 0; i + 3 < base->rgba8.size(); i += 4) base->rgba8[i + 3] = alpha->rgba8[i];
    Texture t;
    t.name = from_diffuse ? om.diffuse_texture : om.alpha_texture;
    t.width = base->width;
    t.height = base->height;
    t.rgba8 = std::move(base->rgba8);
    scene.textures.push_back(std::move(t));
    m.texture[CLP_TEX_BASE] = int(scene.textures.size() - 1);
    return m;
}

}  // namespace clpath
