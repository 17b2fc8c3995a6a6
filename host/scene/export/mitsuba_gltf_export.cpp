#include "scene/export/mitsuba_gltf_export.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "scene/json_fields.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::string num(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
std::string vec(glm::vec3 v) { return std::string("[") + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

const char* wrap_name(std::uint32_t w) {
    switch (w) {
    case CLP_WRAP_CLAMP: return "clamp";
    case CLP_WRAP_MIRROR: return "mirror";
    default: return "repeat";
    }
}

// The texel file of texture `index`, written once however often it is used.
std::string texel_file(const Scene& scene, int index, MitsubaTextureFiles& tex) {
    if (auto it = tex.written.find(index); it != tex.written.end()) return it->second;
    const Texture& t = scene.textures.at(std::size_t(index));
    const std::string file = tex.stem + "-tex" + std::to_string(index) + (t.is_float ? ".rgba32f" : ".rgba8");
    std::string bytes(t.texel_bytes(), '\0');
    if (t.is_float) std::memcpy(bytes.data(), t.rgba32.data(), bytes.size());
    else std::memcpy(bytes.data(), t.rgba8.data(), bytes.size());
    tex.files.emplace_back(file, std::move(bytes));
    return tex.written[index] = file;
}

// A bitmap texture of one use of texture `index`: `channels` ("rgb", "g",
// "b", "a") decoded from sRGB or not, times `scale` (one factor per channel).
std::string bitmap(const Scene& scene, int index, const std::string& channels, bool srgb, const std::string& scale,
                   MitsubaTextureFiles& tex, double normal_scale = 1) {
    const Texture& t = scene.textures.at(std::size_t(index));
    if (t.wrap_s != t.wrap_t)
        throw Error("texture '" + t.name + "': wrap modes " + wrap_name(t.wrap_s) + " (s) and " + wrap_name(t.wrap_t) +
                    " (t) differ, and Mitsuba's bitmap has one for both axes");
    const std::string file = texel_file(scene, index, tex);
    return std::string("{\"type\": \"bitmap\", \"raw\": true, \"filter_type\": \"") +
           (t.nearest ? "nearest" : "bilinear") + "\", \"wrap_mode\": \"" + wrap_name(t.wrap_s) +
           "\", \"clpath_texture\": {\"file\": " + jsonf::quote(file) + ", \"width\": " + std::to_string(t.width) +
           ", \"height\": " + std::to_string(t.height) + ", \"format\": \"" + (t.is_float ? "rgba32f" : "rgba8") +
           "\", \"channels\": \"" + channels + "\", \"srgb\": " + (srgb && !t.is_float ? "true" : "false") +
           ", \"scale\": " + scale + (normal_scale != 1 ? ", \"normal_scale\": " + num(normal_scale) : "") + "}}";
}

bool has(const SceneMaterial& m, unsigned slot) { return m.texture[slot] != CLP_NO_TEXTURE; }

// A texture's channel c (0..3) as a fraction, over all texels: its least and greatest.
std::pair<double, double> channel_range(const Texture& t, int c) {
    double lo = INFINITY, hi = -INFINITY;
    const std::size_t n = std::size_t(t.width) * std::size_t(t.height);
    for (std::size_t i = 0; i < n; ++i) {
        const double v = t.is_float ? double(t.rgba32[4 * i + std::size_t(c)]) : t.rgba8[4 * i + std::size_t(c)] / 255.0;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    return {lo, hi};
}

// Refuses a normal-mapped material whose tangent frame Mitsuba would build
// differently: clpath takes stored tangents when the mesh has them, and flips
// the bitangent where the UVs are mirrored (glTF's tangent w); normalmap
// always uses dp/du and n x dp/du.
void check_normal_frame(const Scene& scene, std::uint32_t mi, const std::string& name) {
    if (scene.uvs.empty()) throw Error("material '" + name + "': a normal map on a mesh without texture coordinates");
    for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
        if (scene.triangle_material[t] != mi) continue;
        if (!scene.tangents.empty())
            for (int j = 0; j < 3; ++j)
                if (glm::vec3(scene.tangents[3 * t + j]) != glm::vec3(0))
                    throw Error("material '" + name + "': the mesh stores tangents, and Mitsuba's normalmap derives "
                                "its frame from the texture coordinates");
        const glm::dvec3 v0(scene.vertices[3 * t]), e1 = glm::dvec3(scene.vertices[3 * t + 1]) - v0,
            e2 = glm::dvec3(scene.vertices[3 * t + 2]) - v0;
        const glm::dvec2 uv0(scene.uvs[3 * t]), d1 = glm::dvec2(scene.uvs[3 * t + 1]) - uv0,
            d2 = glm::dvec2(scene.uvs[3 * t + 2]) - uv0;
        const double r = d1.x * d2.y - d2.x * d1.y;
        if (r == 0) continue;
        const glm::dvec3 dpdu = (e1 * d2.y - e2 * d1.y) / r, dpdv = (e2 * d1.x - e1 * d2.x) / r;
        if (glm::dot(glm::cross(glm::cross(e1, e2), dpdu), dpdv) > 0)
            throw Error("material '" + name + "': triangle " + std::to_string(t) +
                        " has mirrored texture coordinates (bitangent sign -1), which Mitsuba's normalmap does not model");
    }
}

}  // namespace

bool mitsuba_gltf_has_cutout(const SceneMaterial& m) {
    if (m.kind != CLP_MAT_GLTF) return false;
    if (m.alpha_mode == CLP_ALPHA_BLEND) return m.alpha < 1 || has(m, CLP_TEX_BASE);
    if (m.alpha_mode == CLP_ALPHA_MASK) return has(m, CLP_TEX_BASE);
    return false;
}

bool mitsuba_gltf_invisible(const SceneMaterial& m) {
    return m.kind == CLP_MAT_GLTF && m.alpha_mode == CLP_ALPHA_MASK && !has(m, CLP_TEX_BASE) && !(m.alpha >= m.alpha_cutoff);
}

std::string mitsuba_gltf_radiance(const Scene& scene, const SceneMaterial& m, MitsubaTextureFiles& tex) {
    const glm::vec3 e = load3(m.emission);
    if (m.kind == CLP_MAT_GLTF && has(m, CLP_TEX_EMISSION))
        return bitmap(scene, m.texture[CLP_TEX_EMISSION], "rgb", true, vec(e), tex);
    return "{\"type\": \"rgb\", \"value\": " + vec(e) + "}";
}

std::string mitsuba_vertex_colour_product(const std::string& texture) {
    return "{\"type\": \"product\", \"texture_0\": " + texture +
           ", \"texture_1\": {\"type\": \"mesh_attribute\", \"name\": \"vertex_color\"}}";
}

std::string mitsuba_gltf_bsdf(const Scene& scene, std::uint32_t mi, const std::string& name, MitsubaTextureFiles& tex,
                              bool colours) {
    const SceneMaterial& m = scene.materials.at(mi);
    if (emits(m) && m.alpha_mode != CLP_ALPHA_OPAQUE)
        throw Error("material '" + name + "': an emitter with alpha " + (m.alpha_mode == CLP_ALPHA_MASK ? "MASK" : "BLEND") +
                    " (Mitsuba's area light ignores the BSDF's opacity)");
    const glm::vec3 c = load3(m.albedo);
    std::string base = has(m, CLP_TEX_BASE) ? bitmap(scene, m.texture[CLP_TEX_BASE], "rgb", true, vec(c), tex)
                                            : "{\"type\": \"rgb\", \"value\": " + vec(c) + "}";
    if (colours) base = mitsuba_vertex_colour_product(base);
    // roughness x G and metallic x B of the metallic-roughness texture.
    double rough_lo = m.roughness, metal_lo = m.metallic;
    std::string rough = num(m.roughness), metal = num(m.metallic);
    if (has(m, CLP_TEX_MR)) {
        const int i = m.texture[CLP_TEX_MR];
        rough_lo *= channel_range(scene.textures.at(std::size_t(i)), 1).first;
        metal_lo *= channel_range(scene.textures.at(std::size_t(i)), 2).first;
        rough = bitmap(scene, i, "g", false, num(m.roughness), tex);
        metal = bitmap(scene, i, "b", false, num(m.metallic), tex);
    }
    // The layers: factors times their textures (weight R, roughness G, transmission R).
    const bool coat = m.clearcoat > 0, transmits = m.transmission > 0;
    std::string layers;
    if (coat) {
        if (has(m, CLP_TEX_CLEARCOAT_NORMAL))
            throw Error("material '" + name + "': a clear coat with its own normal map (Mitsuba's normalmap bends "
                        "the whole BSDF, not one layer)");
        layers += ", \"clearcoat\": " + (has(m, CLP_TEX_CLEARCOAT)
                                             ? bitmap(scene, m.texture[CLP_TEX_CLEARCOAT], "r", false, num(m.clearcoat), tex)
                                             : num(m.clearcoat));
        layers += ", \"clearcoat_roughness\": " +
                  (has(m, CLP_TEX_CLEARCOAT_ROUGHNESS)
                       ? bitmap(scene, m.texture[CLP_TEX_CLEARCOAT_ROUGHNESS], "g", false, num(m.clearcoat_roughness), tex)
                       : num(m.clearcoat_roughness));
    }
    if (transmits) {
        if (has(m, CLP_TEX_NORMAL))
            throw Error("material '" + name + "': transmission with a normal map (Mitsuba's twosided, which the "
                        "normal map's export needs, takes no transmitting BSDF)");
        layers += ", \"transmits\": true, \"transmission\": " +
                  (has(m, CLP_TEX_TRANSMISSION)
                       ? bitmap(scene, m.texture[CLP_TEX_TRANSMISSION], "r", false, num(m.transmission), tex)
                       : num(m.transmission));
    }
    // principled clamps alpha at 1e-4, clpath at 1e-3 (CLP_SMOOTH_ALPHA):
    // principled only where that never matters.
    std::string b;
    if (metal_lo >= 1 && rough_lo * rough_lo >= 1e-3 && layers.empty())
        b = "{\"type\": \"principled\", \"base_color\": " + base + ", \"metallic\": 1.0, \"roughness\": " + rough +
            ", \"specular\": 0.5, \"spec_tint\": 0.0, \"anisotropic\": 0.0, \"sheen\": 0.0, \"clearcoat\": 0.0, "
            "\"spec_trans\": 0.0}";
    else
        b = "{\"type\": \"gltf_metallic_roughness\", \"base_color\": " + base + ", \"roughness\": " + rough +
            ", \"metallic\": " + metal + ", \"ior\": " + num(m.ior) + layers + "}";
    if (has(m, CLP_TEX_NORMAL)) {
        // normalmap reads its normal in the hit's shading frame, and twosided
        // hands the back face to its second BSDF with the directions mirrored
        // through that frame's tangent plane: the back's normal map has x and
        // y negated, so that it bends the reversed normal as clpath does
        // (glTF: a back face's normal, mapped one included, is reversed).
        // Inside, the BSDF is one-sided: a view below the mapped normal sees
        // nothing, as in clpath.
        check_normal_frame(scene, mi, name);
        const int t = m.texture[CLP_TEX_NORMAL];
        auto mapped = [&](double flip) {
            return "{\"type\": \"normalmap\", \"normalmap\": " +
                   bitmap(scene, t, "rgb", false, "1", tex, m.normal_scale * flip) + ", \"bsdf\": " + b + "}";
        };
        b = "{\"type\": \"twosided\", \"bsdf_0_front\": " + mapped(1) + ", \"bsdf_1_back\": " + mapped(-1) + "}";
    } else if (!transmits) {  // a transmitting one is two-sided itself (benchmarks/references/gltf_bsdf.py)
        b = "{\"type\": \"twosided\", \"bsdf\": " + b + "}";
    }
    if (mitsuba_gltf_has_cutout(m)) {
        std::string cover = has(m, CLP_TEX_BASE) ? bitmap(scene, m.texture[CLP_TEX_BASE], "a", false, num(m.alpha), tex)
                                                 : "{\"type\": \"uniform\", \"value\": " + num(m.alpha) + "}";
        if (m.alpha_mode == CLP_ALPHA_MASK)
            cover = "{\"type\": \"threshold\", \"cutoff\": " + num(m.alpha_cutoff) + ", \"texture\": " + cover + "}";
        b = "{\"type\": \"mask\", \"opacity\": " + cover + ", \"bsdf\": " + b + "}";
    }
    return b;
}

}  // namespace clpath
