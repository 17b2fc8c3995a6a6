#include "scene/export/mitsuba_export.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "scene/json_fields.hpp"
#include "scene/export/mitsuba_gltf_export.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// %.9g reads back as the same float; %.17g the same double.
std::string num(double v, const char* fmt = "%.9g") {
    char buf[40];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}
std::string jvec(glm::dvec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }
std::string jpos(glm::dvec3 v) {
    return "[" + num(v.x, "%.17g") + ", " + num(v.y, "%.17g") + ", " + num(v.z, "%.17g") + "]";
}
std::string rgb(glm::vec3 c) { return "{\"type\": \"rgb\", \"value\": " + jvec(c) + "}"; }


// File-name-safe and unique: letters, digits, '_', '-'; others become '_'.
std::string safe_name(const std::string& name, std::set<std::string>& taken) {
    std::string s = name.empty() ? "material" : name;
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) c = '_';
    std::string unique = s;
    for (int i = 2; !taken.insert(unique).second; ++i) unique = s + "_" + std::to_string(i);
    return unique;
}

// The BSDF that scatters as clpath's material does (see the header); a
// diffuse reflectance times the vertex colours when `colours`.
std::string bsdf(const Material& m, bool colours) {
    const glm::vec3 c = load3(m.albedo);
    const double alpha = double(m.roughness) * m.roughness;
    const bool smooth = alpha < 1e-3;  // CLP_SMOOTH_ALPHA in kernels/materials.cl
    auto twosided = [](const std::string& b) { return "{\"type\": \"twosided\", \"bsdf\": " + b + "}"; };
    switch (m.kind) {
    case CLP_MAT_MIRROR:
        return twosided("{\"type\": \"conductor\", \"material\": \"none\", \"specular_reflectance\": " + rgb(c) + "}");
    case CLP_MAT_CONDUCTOR:
        // principled's metallic lobe is Schlick's F0 + (1 - F0)(1 - cos)^5 with
        // F0 = base_color (its eta only picks that branch for eta > 1); its
        // alpha is roughness^2, clamped below at 1e-4 (clpath: a delta lobe
        // below alpha 1e-3).
        return twosided("{\"type\": \"principled\", \"base_color\": " + rgb(c) +
                        ", \"metallic\": 1.0, \"roughness\": " + num(smooth ? 0.0 : m.roughness) +
                        ", \"specular\": 0.5, \"spec_tint\": 0.0, \"anisotropic\": 0.0, \"sheen\": 0.0, "
                        "\"clearcoat\": 0.0, \"spec_trans\": 0.0}");
    case CLP_MAT_DIELECTRIC:
        if (smooth)
            return "{\"type\": \"dielectric\", \"int_ior\": " + num(m.ior) +
                   ", \"ext_ior\": 1.0, \"specular_transmittance\": " + rgb(c) + "}";
        return "{\"type\": \"roughdielectric\", \"distribution\": \"ggx\", \"alpha\": " + num(alpha) +
               ", \"int_ior\": " + num(m.ior) + ", \"ext_ior\": 1.0, \"specular_transmittance\": " + rgb(c) + "}";
    case CLP_MAT_DIFFUSE:
        return twosided("{\"type\": \"diffuse\", \"reflectance\": " +
                        (colours ? mitsuba_vertex_colour_product(rgb(c)) : rgb(c)) + "}");
    default:  // the glTF material has its own writer (mitsuba_gltf_export.hpp)
        throw Error(std::string("internal: no Mitsuba BSDF for the material kind ") + material_kind_name(m.kind));
    }
}

// Some corner of these triangles has a colour other than white.
bool vertex_colours_matter(const Scene& scene, const std::vector<std::size_t>& tris) {
    if (scene.colors.empty()) return false;
    for (std::size_t t : tris)
        for (int j = 0; j < 3; ++j)
            if (scene.colors[3 * t + j] != glm::vec4(1)) return true;
    return false;
}

}  // namespace

MitsubaExport export_mitsuba_scene(const Scene& scene, const std::string& stem, const std::string& source) {
    if (scene.triangle_count() == 0) throw Error("the scene has no triangles");
    // Mitsuba is single precision too: the scene is moved so that the camera
    // sits at the origin (in double, then rounded once), which takes nothing
    // from a scene near the origin and keeps one far from it (scenes/hard)
    // from being rendered with ulps of 1/16.
    const glm::dvec3 shift(scene.camera.eye);
    auto at = [&](glm::vec3 p) { return glm::dvec3(p) - shift; };
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (auto v : scene.vertices) {
        lo = glm::min(lo, at(v));
        hi = glm::max(hi, at(v));
    }
    const double diag = glm::length(hi - lo) + glm::length(0.5 * (lo + hi));
    // A two-sided emitter's back copy lies this far behind its front.
    const double back_offset = 1e-6 * glm::length(hi - lo);

    MitsubaExport out;
    MitsubaTextureFiles tex;
    tex.stem = stem;
    std::set<std::string> taken;
    std::string shapes, notes;
    bool cutouts = false;
    auto note = [&](const std::string& s) { notes += std::string(notes.empty() ? "" : ", ") + jsonf::quote(s); };
    for (std::uint32_t mi = 0; mi < scene.materials.size(); ++mi) {
        std::vector<std::size_t> tris;
        for (std::size_t t = 0; t < scene.triangle_count(); ++t)
            if (scene.triangle_material[t] == mi) tris.push_back(t);
        if (tris.empty()) continue;
        const SceneMaterial& m = scene.materials[mi];
        const std::string name = safe_name(mi < scene.material_names.size() ? scene.material_names[mi] : "", taken);
        if (mitsuba_gltf_invisible(m)) {
            note("'" + name + "': alpha MASK with a constant coverage below the cutoff: never hit, left out");
            continue;
        }
        const bool normals = !scene.normals.empty();
        const bool uvs = !scene.uvs.empty();
        const bool two_sided = emits(m) && (m.flags & CLP_MATF_TWO_SIDED_EMISSION);
        // Vertex colours multiply the base colour (diffuse albedo, glTF base
        // colour); a material whose triangles are all white ignores them.
        std::string colour_file;
        const bool colours = vertex_colours_matter(scene, tris);
        if (colours) {
            if (m.kind != CLP_MAT_DIFFUSE && m.kind != CLP_MAT_GLTF)
                throw Error("material '" + name + "': vertex colours on a material other than diffuse or glTF");
            if (emits(m)) throw Error("material '" + name + "': vertex colours on an emitter");
            if (m.alpha_mode != CLP_ALPHA_OPAQUE)
                for (std::size_t t : tris)
                    for (int j = 0; j < 3; ++j)
                        if (scene.colors[3 * t + j].w != 1)
                            throw Error("material '" + name + "': vertex alpha with alpha " +
                                        (m.alpha_mode == CLP_ALPHA_MASK ? "MASK" : "BLEND"));
            colour_file = stem + "-" + name + ".rgb32f";
            std::string bytes;
            for (std::size_t t : tris)
                for (int j = 0; j < 3; ++j) {
                    const glm::vec3 c(scene.colors[3 * t + j]);
                    bytes.append(reinterpret_cast<const char*>(&c), sizeof c);
                }
            out.textures.emplace_back(colour_file, std::move(bytes));
        }
        std::string b;
        if (m.kind == CLP_MAT_GLTF) {
            b = mitsuba_gltf_bsdf(scene, mi, name, tex, colours);
            cutouts = cutouts || mitsuba_gltf_has_cutout(m);
            if (b.find("\"principled\"") != std::string::npos)
                note("'" + name + "': metallic 1 as principled: Smith masking separable (Mitsuba) vs height-correlated (clpath)");
        } else {
            // Only the glTF material carries textures and alpha (scene files,
            // glTF and textured MTL make it); anything else would be lost.
            for (int t : m.texture)
                if (t != CLP_NO_TEXTURE) throw Error("material '" + name + "': a texture on a material that is not the glTF one");
            if (m.alpha_mode != CLP_ALPHA_OPAQUE) throw Error("material '" + name + "': alpha on a material that is not the glTF one");
            b = bsdf(m, colours);
        }
        out.json += "    \"bsdf-" + name + "\": " + b + ",\n";
        if ((m.kind == CLP_MAT_CONDUCTOR || m.kind == CLP_MAT_DIELECTRIC) && double(m.roughness) * m.roughness >= 1e-3)
            note("'" + name + "': Smith masking separable (Mitsuba) vs height-correlated (clpath)");
        for (int side = 0; side < (two_sided ? 2 : 1); ++side) {
            const std::string file = stem + "-" + name + (side ? "-back" : "") + ".obj";
            std::string obj = "# clpath export of '" + scene.name + "' from " + source + ", material '" + name + "'" +
                              (side ? ": the back-facing copy of a two-sided emitter" : "") + "\n";
            std::string faces;
            std::size_t k = 0;
            for (std::size_t t : tris) {
                glm::dvec3 p[3];
                for (int j = 0; j < 3; ++j) p[j] = at(scene.vertices[3 * t + j]);
                glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
                const double len = glm::length(n);
                if (side) {
                    // Reversed winding (its front is the original's back), moved behind the original.
                    std::swap(p[1], p[2]);
                    if (len > 0)
                        for (auto& q : p) q -= n / len * back_offset;
                }
                for (int j = 0; j < 3; ++j) obj += "v " + num(p[j].x) + " " + num(p[j].y) + " " + num(p[j].z) + "\n";
                const int order[3] = {0, side ? 2 : 1, side ? 1 : 2};
                if (normals)
                    for (int j : order) {
                        glm::vec3 sn = scene.normals[3 * t + j];
                        // Zero is clpath's "none here, shade flat" (an instanced scene
                        // flattened gives its flat triangles that); Mitsuba refuses it.
                        if (sn == glm::vec3(0) && len > 0) sn = glm::vec3(n / len);
                        if (side) sn = -sn;
                        obj += "vn " + num(sn.x) + " " + num(sn.y) + " " + num(sn.z) + "\n";
                    }
                // clpath's v, row 0 of the image at v = 0 (glTF's), is
                // Mitsuba's with flip_tex_coords off.
                if (uvs)
                    for (int j : order) obj += "vt " + num(scene.uvs[3 * t + j].x) + " " + num(scene.uvs[3 * t + j].y) + "\n";
                faces += "f";
                for (int j = 1; j <= 3; ++j) {
                    const std::string i = std::to_string(k + j);
                    faces += " " + i + (uvs ? "/" + i : std::string(normals ? "/" : "")) + (normals ? "/" + i : "");
                }
                faces += "\n";
                k += 3;
            }
            out.meshes.emplace_back(file, obj + faces);
            shapes += "    \"shape-" + name + (side ? "-back" : "") + "\": {\"type\": \"obj\", \"filename\": " +
                      jsonf::quote(file) + ", \"face_normals\": " + (normals ? "false" : "true") +
                      (uvs ? ", \"flip_tex_coords\": false" : "") +
                      (colours ? ", \"clpath_vertex_colors\": " + jsonf::quote(colour_file) : "") +
                      ", \"bsdf\": {\"type\": \"ref\", \"id\": \"bsdf-" + name + "\"}" +
                      (emits(m) ? ", \"emitter\": {\"type\": \"area\", \"radiance\": " + mitsuba_gltf_radiance(scene, m, tex) + "}"
                                : "") +
                      "},\n";
        }
    }
    out.json += shapes;

    int li = 0;
    for (const PunctualLight& l : scene.lights) {
        const std::string key = "    \"light-" + std::to_string(li++) + "\": ";
        switch (l.type) {
        case PunctualLight::Type::Point:
            out.json += key + "{\"type\": \"point\", \"position\": " + jpos(at(l.position)) +
                        ", \"intensity\": " + rgb(l.intensity) + "},\n";
            break;
        case PunctualLight::Type::Spot:
            // Mitsuba's own falloff (linear in angle) is switched off (beam
            // width = cutoff); the script multiplies in clpath's falloff,
            // smoothstep(cos outer, cos inner, cos theta), as a texture.
            out.json += key + "{\"type\": \"spot\", \"clpath_look_at\": {\"origin\": " + jpos(at(l.position)) +
                        ", \"direction\": " + jvec(l.direction) + "}, \"cutoff_angle\": " +
                        num(l.spot_outer_degrees) + ", \"beam_width\": " + num(l.spot_outer_degrees) +
                        ", \"intensity\": " + rgb(l.intensity) + ", \"clpath_spot_falloff\": {\"inner_degrees\": " +
                        num(l.spot_inner_degrees) + ", \"outer_degrees\": " + num(l.spot_outer_degrees) + "}},\n";
            break;
        case PunctualLight::Type::Directional:
            out.json += key + "{\"type\": \"directional\", \"direction\": " + jvec(l.direction) +
                        ", \"irradiance\": " + rgb(l.intensity) + "},\n";
            break;
        }
    }
    const Environment& env = scene.environment;
    if (!env.image.empty()) {
        // clpath: u = 0.5 + atan2(x, -z) / 2pi of the direction turned by the
        // rotation about +y; Mitsuba: u = atan2(x, -z) / 2pi of to_world^-1 d.
        // The script builds to_world from these and looks texels up without
        // filtering, as clpath does.
        out.json += "    \"environment\": {\"type\": \"envmap\", \"filename\": " + jsonf::quote(std::filesystem::absolute(env.image).string()) +
                    ", \"scale\": " + num(env.scale) + ", \"clpath_env_rotation_degrees\": " +
                    num(env.rotation_degrees) + "},\n";
    } else if (env.emits()) {
        out.json += "    \"environment\": {\"type\": \"constant\", \"radiance\": " + rgb(env.color) + "},\n";
    }

    const Camera& c = scene.camera;
    if (c.ortho_half_height > 0)
        throw Error("the scene's camera is orthographic, which the exported file's camera cannot describe (a pinhole "
                    "camera only)");
    const SceneRenderDefaults& r = scene.render;
    // A thin lens is Mitsuba's thinlens sensor: the same disk of that radius
    // about the eye, focused on the plane at that distance along the view.
    const std::string lens = c.has_lens() ? "\"aperture_radius\": " + num(c.aperture_radius) +
                                                ", \"focus_distance\": " + num(c.resolved_focus_distance()) + ", "
                                          : std::string();
    // clpath's max_depth counts scattering events, Mitsuba's path segments:
    // depth d in clpath ends with the segment d + 1.
    const std::string head =
        "{\n  \"clpath\": {\"source\": " + jsonf::quote(source) + ", \"name\": " + jsonf::quote(scene.name) +
        ", \"width\": " + std::to_string(c.width) + ", \"height\": " + std::to_string(c.height) +
        ", \"spp\": " + std::to_string(r.spp) + ", \"max_depth\": " + std::to_string(r.max_depth) +
        ", \"shift\": " + jpos(-shift) + ", \"notes\": [" + notes + "]},\n  \"scene\": {\n    \"type\": \"scene\",\n" +
        "    \"integrator\": {\"type\": \"" + (cutouts ? "volpath" : "path") + "\", \"max_depth\": " + std::to_string(r.max_depth + 1) +
        ", \"hide_emitters\": false},\n" +
        "    \"sensor\": {\"type\": \"" + (c.has_lens() ? "thinlens" : "perspective") + "\", " + lens +
        "\"fov\": " + num(c.vfov_degrees) +
        ", \"fov_axis\": \"y\", \"near_clip\": " + num(1e-6 * diag) + ", \"far_clip\": " + num(1e3 * diag) +
        ", \"clpath_look_at\": {\"origin\": " + jpos(at(c.eye)) + ", \"target\": " + jpos(at(c.target)) +
        ", \"up\": " + jvec(c.up) + "},\n      \"film\": {\"type\": \"hdrfilm\", \"width\": " + std::to_string(c.width) +
        ", \"height\": " + std::to_string(c.height) +
        ", \"rfilter\": {\"type\": \"box\"}, \"pixel_format\": \"rgb\", \"component_format\": \"float32\"},\n" +
        "      \"sampler\": {\"type\": \"independent\", \"sample_count\": " + std::to_string(r.spp) + "}},\n";
    // No trailing comma after the last entry.
    if (out.json.size() >= 2 && out.json.compare(out.json.size() - 2, 2, ",\n") == 0)
        out.json.replace(out.json.size() - 2, 2, "\n");
    out.json = head + out.json + "  }\n}\n";
    out.textures.insert(out.textures.end(), tex.files.begin(), tex.files.end());
    return out;
}

}  // namespace clpath
