#include "scene/export/obj_export.hpp"

#include <cstdio>
#include <cctype>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

#include "scene/json_fields.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// %.9g: every float reads back as the same float.
std::string num(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}
std::string vec(glm::vec3 v, const char* sep = " ") { return num(v.x) + sep + num(v.y) + sep + num(v.z); }
std::string json_vec(glm::vec3 v) { return std::string("[") + vec(v, ", ") + "]"; }


// MTL names are one token: letters, digits, '_', '-', '.'; others become '_'.
std::string mtl_name(const std::string& name, std::set<std::string>& taken) {
    std::string s = name.empty() ? "material" : name;
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
    std::string unique = s;
    for (int i = 2; !taken.insert(unique).second; ++i) unique = s + "_" + std::to_string(i);
    return unique;
}

}  // namespace

ObjMeshText obj_mesh_text(const Scene& scene, const std::string& stem, const std::string& source) {
    std::vector<bool> used(scene.materials.size(), false);
    for (auto m : scene.triangle_material) used.at(m) = true;
    ObjMeshText m;
    std::set<std::string> taken;
    m.names.assign(scene.materials.size(), "");
    std::vector<std::string>& names = m.names;
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (used[i]) names[i] = mtl_name(i < scene.material_names.size() ? scene.material_names[i] : "", taken);

    m.mtl = "# clpath export of '" + scene.name + "': Lambertian reflectance Kd, emitted radiance Ke (W sr^-1 m^-2)\n";
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material& mat = scene.materials[i];
        m.mtl += "\nnewmtl " + names[i] + "\nKd " + vec(load3(mat.albedo)) + "\nKs 0 0 0\n";
        if (emits(mat)) m.mtl += "Ke " + vec(load3(mat.emission)) + "\n";
        m.mtl += "illum 1\n";
    }

    // Shared vertices (by exact value); faces keep their winding, so the
    // front faces (and one-sided emitters) stay where they were.
    m.obj = "# clpath export of '" + scene.name + "' from " + source + ": " + std::to_string(scene.triangle_count()) +
            " triangles, counter-clockwise = front\nmtllib " + stem + ".mtl\n";
    std::map<std::tuple<float, float, float>, std::size_t> index;
    std::vector<std::size_t> corner(scene.vertices.size());
    for (std::size_t v = 0; v < scene.vertices.size(); ++v) {
        const glm::vec3 p = scene.vertices[v];
        auto [it, added] = index.emplace(std::make_tuple(p.x, p.y, p.z), index.size() + 1);
        if (added) m.obj += "v " + vec(p) + "\n";
        corner[v] = it->second;
    }
    std::uint32_t current = ~0u;
    for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
        if (scene.triangle_material[t] != current) {
            current = scene.triangle_material[t];
            m.obj += "usemtl " + names[current] + "\n";
        }
        m.obj += "f " + std::to_string(corner[3 * t]) + " " + std::to_string(corner[3 * t + 1]) + " " +
                 std::to_string(corner[3 * t + 2]) + "\n";
    }
    return m;
}

ObjExport export_obj_scene(const Scene& scene, const std::string& stem, const std::string& source) {
    // What Cycles would model differently is refused, so that a reference
    // rendered from the export is a reference for this very scene.
    std::vector<bool> used(scene.materials.size(), false);
    for (auto m : scene.triangle_material) used.at(m) = true;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i] || scene.materials[i].kind == CLP_MAT_DIFFUSE) continue;
        const std::string name = i < scene.material_names.size() ? scene.material_names[i] : std::to_string(i);
        throw Error("material '" + name + "' is a " + material_kind_name(scene.materials[i].kind) +
                    ": only diffuse and emissive surfaces are exported (Cycles' glossy and glass BSDFs differ "
                    "from clpath's; use a high-sample clpath render as the reference for such scenes)");
    }
    if (!scene.normals.empty())
        throw Error("the scene has shading normals: only flat-shaded scenes are exported (Cycles interpolates and "
                    "bounds shading normals differently)");
    if (!scene.lights.empty())
        throw Error("the scene has " + std::to_string(scene.lights.size()) +
                    " punctual light(s): only emissive surfaces are exported (Blender's lamp units differ)");
    if (!scene.environment.image.empty())
        throw Error("the scene's environment is an image: only a constant environment colour is exported");
    if (scene.triangle_count() == 0) throw Error("the scene has no triangles");

    const ObjMeshText mesh = obj_mesh_text(scene, stem, source);
    const std::vector<std::string>& names = mesh.names;
    ObjExport out;
    out.obj = mesh.obj;
    out.mtl = mesh.mtl;

    // The scene file: MTL has no two-sided emission, so those materials are
    // given here and mapped onto the mesh by name.
    std::string materials, mapping;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (!used[i] || !emits(m) || !(m.flags & CLP_MATF_TWO_SIDED_EMISSION)) continue;
        materials += std::string(materials.empty() ? "" : ",\n") + "    " + jsonf::quote(names[i]) +
                     ": { \"type\": \"emitter\", \"emission\": " + json_vec(load3(m.emission)) +
                     ", \"albedo\": " + json_vec(load3(m.albedo)) + ", \"two_sided\": true }";
        mapping += std::string(mapping.empty() ? "" : ", ") + jsonf::quote(names[i]) + ": " + jsonf::quote(names[i]);
    }
    const Camera& c = scene.camera;
    if (c.ortho_half_height > 0)
        throw Error("the scene's camera is orthographic, which the exported file's camera cannot describe (a pinhole "
                    "camera only)");
    const SceneRenderDefaults& r = scene.render;
    out.json = "{\n  \"name\": " + jsonf::quote(scene.name) + ",\n  \"description\": " +
               jsonf::quote("Exported by clpath export from " + source +
                           ": the mesh and its MTL materials (Kd reflectance, Ke radiance, one-sided), with the "
                           "camera, the render settings and the two-sided emitters here.") +
               ",\n  \"camera\": { \"eye\": " + json_vec(c.eye) + ", \"target\": " + json_vec(c.target) +
               ", \"up\": " + json_vec(c.up) + ", \"vfov\": " + num(c.vfov_degrees) +
               (c.has_lens() ? ", \"aperture_radius\": " + num(c.aperture_radius) +
                                   ", \"focus_distance\": " + num(c.resolved_focus_distance())
                             : std::string()) +
               ", \"resolution\": [" +
               std::to_string(c.width) + ", " + std::to_string(c.height) + "] },\n  \"render\": { \"spp\": " +
               std::to_string(r.spp) + ", \"max_depth\": " + std::to_string(r.max_depth) +
               ", \"russian_roulette\": " + jsonf::quote(r.russian_roulette) + ", \"integrator\": " +
               jsonf::quote(r.integrator) + ", \"seed\": " + std::to_string(r.seed) + " },\n";
    if (!materials.empty()) out.json += "  \"materials\": {\n" + materials + "\n  },\n";
    out.json += "  \"objects\": [\n    { \"type\": \"mesh\", \"file\": " + jsonf::quote(stem + ".obj") +
                ", \"smooth\": false" + (mapping.empty() ? "" : ", \"materials\": { " + mapping + " }") + " }\n  ]";
    if (scene.environment.emits())
        out.json += ",\n  \"environment\": { \"color\": " + json_vec(scene.environment.color) + " }";
    out.json += "\n}\n";
    return out;
}

}  // namespace clpath
