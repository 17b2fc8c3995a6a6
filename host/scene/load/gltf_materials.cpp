// glTF materials and their textures, onto CLP_MAT_GLTF (docs/scene-format.md
// lists what is read and what is ignored).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "scene/load/gltf_parts.hpp"
#include "util/error.hpp"

namespace clpath::gltf {
namespace {

std::uint32_t wrap_mode(int gl) {
    switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return CLP_WRAP_CLAMP;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return CLP_WRAP_MIRROR;
    default: return CLP_WRAP_REPEAT;
    }
}

// A file name whose extension tells OpenImageIO the format.
// The name the decoder gets: its extension is the format hint, and its
// messages name it, so an external file is named by the path it resolved to.
std::string format_hint(const tinygltf::Image& img, std::size_t index, const std::string& file) {
    const bool external = !img.uri.empty() && img.uri.rfind("data:", 0) != 0 && img.uri.rfind(kDataUriPrefix, 0) != 0;
    if (external && std::filesystem::path(uri_path(file, img.uri)).has_extension()) return uri_path(file, img.uri);
    if (img.mimeType == "image/png") return "image.png";
    if (img.mimeType == "image/jpeg") return "image.jpg";
    if (external) return uri_path(file, img.uri);
    if (img.uri.rfind("data:image/png", 0) == 0) return "image.png";
    if (img.uri.rfind("data:image/jpeg", 0) == 0) return "image.jpg";
    return "images[" + std::to_string(index) + "]";
}

float factor(const Source& src, double v, const std::string& path, float lo, float hi) {
    if (!(v >= lo && v <= hi)) src.fail(path, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return float(v);
}

float extension_number(const tinygltf::ExtensionMap& ext, const char* name, const char* key, float fallback) {
    auto it = ext.find(name);
    if (it == ext.end() || !it->second.IsObject() || !it->second.Has(key) || !it->second.Get(key).IsNumber()) return fallback;
    return float(it->second.Get(key).GetNumberAsDouble());
}

// A texture reference inside an extension's object (a glTF textureInfo:
// index, texCoord, scale for normal maps, its own extensions), which
// tinygltf leaves as JSON.
struct ExtTexture {
    int index = -1, texcoord = 0;
    double scale = 1;
    tinygltf::ExtensionMap extensions;
};
ExtTexture ext_texture(const Source& src, const tinygltf::Value& ext, const char* key, const std::string& path) {
    ExtTexture t;
    if (!ext.Has(key)) return t;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsInt())
        src.fail(path, "must be a texture reference with an integer 'index'");
    t.index = v.Get("index").GetNumberAsInt();
    if (t.index < 0) src.fail(path + ".index", "must be non-negative, got " + std::to_string(t.index));
    if (v.Has("texCoord") && v.Get("texCoord").IsInt()) t.texcoord = v.Get("texCoord").GetNumberAsInt();
    if (v.Has("scale") && v.Get("scale").IsNumber()) t.scale = v.Get("scale").GetNumberAsDouble();
    if (v.Has("extensions") && v.Get("extensions").IsObject())
        for (const auto& k : v.Get("extensions").Keys()) t.extensions[k] = v.Get("extensions").Get(k);
    return t;
}

// A factor of an extension's object, default when absent, in [0, 1].
float ext_factor(const Source& src, const tinygltf::Value& ext, const char* key, float fallback, const std::string& path) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsNumber()) src.fail(path, "must be a number");
    return factor(src, v.GetNumberAsDouble(), path, 0, 1);
}

// KHR_texture_transform's matrix, uv' = T * R * S * uv (the extension's
// specification, with its rotation's sign), or nothing when absent.
std::optional<glm::mat3> uv_transform(const tinygltf::ExtensionMap& ext) {
    auto it = ext.find("KHR_texture_transform");
    if (it == ext.end() || !it->second.IsObject()) return std::nullopt;
    const tinygltf::Value& v = it->second;
    auto pair = [&](const char* key, float fallback) {
        glm::vec2 out(fallback);
        if (v.Has(key) && v.Get(key).IsArray() && v.Get(key).ArrayLen() == 2)
            for (int i = 0; i < 2; ++i) out[i] = float(v.Get(key).Get(i).GetNumberAsDouble());
        return out;
    };
    const glm::vec2 offset = pair("offset", 0), scale = pair("scale", 1);
    const float r = v.Has("rotation") && v.Get("rotation").IsNumber() ? float(v.Get("rotation").GetNumberAsDouble()) : 0.0f;
    // glm is column-major: each glm::vec3 below is a column.
    const glm::mat3 t(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
    const glm::mat3 rot(glm::vec3(std::cos(r), -std::sin(r), 0), glm::vec3(std::sin(r), std::cos(r), 0), glm::vec3(0, 0, 1));
    const glm::mat3 s(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
    return t * rot * s;
}

class Reader {
public:
    Reader(const Source& src, GltfModel& out) : src_(src), out_(out) {}

    int texture(int index, int texcoord, const std::string& path) {
        if (index < 0) return CLP_NO_TEXTURE;
        const auto& m = src_.model;
        if (std::size_t(index) >= m.textures.size())
            src_.fail(path + ".index", "texture " + std::to_string(index) + " does not exist (the file has " +
                                           std::to_string(m.textures.size()) + ")");
        if (texcoord != 0)
            out_.warnings.push_back(src_.file + ": " + path + ": uses TEXCOORD_" + std::to_string(texcoord) +
                                    "; clpath reads TEXCOORD_0 for every texture");
        const tinygltf::Texture& t = m.textures[std::size_t(index)];
        const std::string tp = "textures[" + std::to_string(index) + "]";
        if (t.source < 0 || std::size_t(t.source) >= m.images.size())
            src_.fail(tp + ".source", "image " + std::to_string(t.source) + " does not exist (the file has " +
                                          std::to_string(m.images.size()) + ")");
        if (t.sampler >= 0 && std::size_t(t.sampler) >= m.samplers.size())
            src_.fail(tp + ".sampler", "sampler " + std::to_string(t.sampler) + " does not exist");
        const auto key = std::make_pair(t.source, t.sampler);
        if (auto it = cache_.find(key); it != cache_.end()) return it->second;

        const tinygltf::Image& img = m.images[std::size_t(t.source)];
        const std::string ip = "images[" + std::to_string(t.source) + "]";
        if (img.image.empty() && !img.uri.empty() && img.uri.rfind("data:", 0) != 0 && img.uri.rfind(kDataUriPrefix, 0) != 0) {
            // The file is missing (check_uris warned, naming the path): a neutral texture, that is none.
            const std::string full = uri_path(src_.file, img.uri);
            std::error_code ec;
            const bool exists = src_.options.file_exists ? src_.options.file_exists(full) : std::filesystem::exists(full, ec);
            if (!exists) return cache_[key] = CLP_NO_TEXTURE;
        }
        if (img.image.empty())
            src_.fail(ip, "no image data (" + (img.uri.empty() ? "bufferView " + std::to_string(img.bufferView)
                                                               : "'" + img.uri.substr(0, 80) + "'") + ")");
        Texture tex;
        try {
            TextureImage ti = src_.options.decode_texture(
                std::string(reinterpret_cast<const char*>(img.image.data()), img.image.size()),
                format_hint(img, std::size_t(t.source), src_.file));
            if (ti.width <= 0 || ti.height <= 0 ||
                (ti.is_float ? ti.rgba32.size() : ti.rgba8.size()) != std::size_t(ti.width) * std::size_t(ti.height) * 4)
                throw Error("the decoder returned no texels");
            tex.width = ti.width;
            tex.height = ti.height;
            tex.is_float = ti.is_float;
            tex.rgba8 = std::move(ti.rgba8);
            tex.rgba32 = std::move(ti.rgba32);
        } catch (const Error& e) {
            src_.fail(ip + " (used by " + path + ")", e.what());
        }
        tex.name = src_.file + ": " + ip;
        if (t.sampler >= 0) {
            const tinygltf::Sampler& s = m.samplers[std::size_t(t.sampler)];
            tex.wrap_s = wrap_mode(s.wrapS);
            tex.wrap_t = wrap_mode(s.wrapT);
            tex.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
        out_.textures.push_back(std::move(tex));
        return cache_[key] = int(out_.textures.size() - 1);
    }

    GltfMaterial material(std::size_t i) {
        const tinygltf::Material& gm = src_.model.materials[i];
        const std::string p = "materials[" + std::to_string(i) + "]";
        const auto& pbr = gm.pbrMetallicRoughness;
        const std::string pp = p + ".pbrMetallicRoughness";
        glm::vec4 base(1);
        if (pbr.baseColorFactor.size() == 4)
            for (int c = 0; c < 4; ++c)
                base[c] = factor(src_, pbr.baseColorFactor[std::size_t(c)], pp + ".baseColorFactor[" + std::to_string(c) + "]", 0, 1);
        SceneMaterial m = gltf_material(glm::vec3(base), factor(src_, pbr.metallicFactor, pp + ".metallicFactor", 0, 1),
                                   factor(src_, pbr.roughnessFactor, pp + ".roughnessFactor", 0, 1));
        m.alpha = base.w;
        glm::vec3 e(0);
        if (gm.emissiveFactor.size() == 3)
            for (int c = 0; c < 3; ++c)
                e[c] = factor(src_, gm.emissiveFactor[std::size_t(c)], p + ".emissiveFactor[" + std::to_string(c) + "]", 0, 1);
        const float strength = extension_number(gm.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1);
        if (!(strength >= 0) || !std::isfinite(strength))
            src_.fail(p + ".extensions.KHR_materials_emissive_strength.emissiveStrength", "must be finite and non-negative");
        store3(m.emission, e * strength);
        m.ior = extension_number(gm.extensions, "KHR_materials_ior", "ior", 1.5f);
        if (!(m.ior >= 1 && m.ior <= 10)) src_.fail(p + ".extensions.KHR_materials_ior.ior", "must be in [1, 10]");
        // glTF emission is from the front face unless the material is double-sided.
        if (gm.doubleSided) m.flags |= CLP_MATF_TWO_SIDED_EMISSION;
        if (gm.alphaMode == "OPAQUE" || gm.alphaMode.empty()) m.alpha_mode = CLP_ALPHA_OPAQUE;
        else if (gm.alphaMode == "MASK") m.alpha_mode = CLP_ALPHA_MASK;
        else if (gm.alphaMode == "BLEND") m.alpha_mode = CLP_ALPHA_BLEND;
        else src_.fail(p + ".alphaMode", "unknown alpha mode '" + gm.alphaMode + "' (OPAQUE, MASK or BLEND)");
        m.alpha_cutoff = factor(src_, gm.alphaCutoff, p + ".alphaCutoff", 0, 1e30f);
        m.texture[CLP_TEX_BASE] = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pp + ".baseColorTexture");
        m.texture[CLP_TEX_MR] = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                        pp + ".metallicRoughnessTexture");
        m.texture[CLP_TEX_NORMAL] = texture(gm.normalTexture.index, gm.normalTexture.texCoord, p + ".normalTexture");
        m.texture[CLP_TEX_EMISSION] = texture(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, p + ".emissiveTexture");
        m.normal_scale = float(gm.normalTexture.scale);
        if (!std::isfinite(m.normal_scale)) src_.fail(p + ".normalTexture.scale", "must be finite");
        // The layers (clear coat, transmission): their textures join the material's (transforms below).
        std::vector<std::pair<ExtTexture, std::string>> layer_textures;
        auto layer_texture = [&](const tinygltf::Value& ext, const char* key, unsigned slot, const std::string& ep) {
            ExtTexture t = ext_texture(src_, ext, key, ep + "." + key);
            m.texture[slot] = texture(t.index, t.texcoord, ep + "." + key);
            if (t.index >= 0) layer_textures.emplace_back(t, ep + "." + key);
            return t;
        };
        if (auto it = gm.extensions.find("KHR_materials_clearcoat"); it != gm.extensions.end()) {
            const std::string ep = p + ".extensions.KHR_materials_clearcoat";
            if (!it->second.IsObject()) src_.fail(ep, "must be an object");
            m.clearcoat = ext_factor(src_, it->second, "clearcoatFactor", 0, ep + ".clearcoatFactor");
            m.clearcoat_roughness = ext_factor(src_, it->second, "clearcoatRoughnessFactor", 0, ep + ".clearcoatRoughnessFactor");
            layer_texture(it->second, "clearcoatTexture", CLP_TEX_CLEARCOAT, ep);
            layer_texture(it->second, "clearcoatRoughnessTexture", CLP_TEX_CLEARCOAT_ROUGHNESS, ep);
            const ExtTexture n = layer_texture(it->second, "clearcoatNormalTexture", CLP_TEX_CLEARCOAT_NORMAL, ep);
            m.clearcoat_normal_scale = float(n.scale);
            if (!std::isfinite(m.clearcoat_normal_scale)) src_.fail(ep + ".clearcoatNormalTexture.scale", "must be finite");
            if (m.clearcoat == 0) {  // no coat: its maps would only cost (the spec's factor multiplies them)
                for (unsigned s : {CLP_TEX_CLEARCOAT, CLP_TEX_CLEARCOAT_ROUGHNESS, CLP_TEX_CLEARCOAT_NORMAL})
                    m.texture[s] = CLP_NO_TEXTURE;
                layer_textures.clear();
            }
        }
        if (auto it = gm.extensions.find("KHR_materials_transmission"); it != gm.extensions.end()) {
            const std::string ep = p + ".extensions.KHR_materials_transmission";
            if (!it->second.IsObject()) src_.fail(ep, "must be an object");
            m.transmission = ext_factor(src_, it->second, "transmissionFactor", 0, ep + ".transmissionFactor");
            const ExtTexture t = layer_texture(it->second, "transmissionTexture", CLP_TEX_TRANSMISSION, ep);
            if (m.transmission == 0 && t.index >= 0) {
                m.texture[CLP_TEX_TRANSMISSION] = CLP_NO_TEXTURE;
                layer_textures.pop_back();
            }
            if (gm.extensions.count("KHR_materials_volume"))
                out_.warnings.push_back(src_.file + ": " + p + ": KHR_materials_volume is not supported; its transmission is "
                                        "rendered thin-walled (light passes the surface without refracting)");
        }
        GltfMaterial out{gm.name.empty() ? p : gm.name, m, std::nullopt};
        // One set of texture coordinates per vertex: the first texture's transform
        // is applied to them (quantisers such as gltfpack give every texture of a
        // material the same one); a different one on another texture is a warning.
        const std::pair<const tinygltf::TextureInfo*, const char*> infos[] = {
            {&pbr.baseColorTexture, ".pbrMetallicRoughness.baseColorTexture"},
            {&pbr.metallicRoughnessTexture, ".pbrMetallicRoughness.metallicRoughnessTexture"}};
        std::optional<glm::mat3> first;
        std::string first_path;
        auto consider = [&](const tinygltf::ExtensionMap& ext, int index, const std::string& tp) {
            if (index < 0) return;
            const std::optional<glm::mat3> t = uv_transform(ext);
            if (first_path.empty()) {
                first = t;
                first_path = tp;
            } else if (t.value_or(glm::mat3(1)) != first.value_or(glm::mat3(1))) {
                out_.warnings.push_back(src_.file + ": " + tp + ": its KHR_texture_transform differs from " + first_path +
                                        "'s; clpath uses " + first_path + "'s for every texture of the material");
            }
        };
        for (const auto& [info, suffix] : infos) consider(info->extensions, info->index, p + suffix);
        consider(gm.normalTexture.extensions, gm.normalTexture.index, p + ".normalTexture");
        consider(gm.occlusionTexture.extensions, -1, p + ".occlusionTexture");
        consider(gm.emissiveTexture.extensions, gm.emissiveTexture.index, p + ".emissiveTexture");
        for (const auto& [t, tp] : layer_textures) consider(t.extensions, t.index, tp);
        out.uv_transform = first;
        return out;
    }

private:
    const Source& src_;
    GltfModel& out_;
    std::map<std::pair<int, int>, int> cache_;
};

}  // namespace

void read_materials(const Source& src, GltfModel& model) {
    Reader r(src, model);
    for (std::size_t i = 0; i < src.model.materials.size(); ++i) model.materials.push_back(r.material(i));
}

}  // namespace clpath::gltf
