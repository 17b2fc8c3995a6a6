#include "scene/load/gltf_support.hpp"

#include <nlohmann/json.hpp>

#include "util/error.hpp"

namespace clpath::gltf {
namespace {

[[noreturn]] void refuse_version(const std::string& version, const std::string& file) {
    throw Error(file + ": glTF " + (version.empty() ? "1.0" : version) +
                " is not supported (glTF 2.0 is); convert the file to glTF 2.0 first");
}

bool is_version_1(const std::string& v) { return v == "1" || v.rfind("1.", 0) == 0; }

// glTF 1.0 keeps its objects in dictionaries by id; 2.0 in arrays.
bool has_version_1_structure(const nlohmann::json& doc) {
    for (const char* section : {"accessors", "bufferViews", "buffers", "meshes", "nodes", "materials", "scenes",
                                "textures", "images", "samplers", "cameras", "skins", "animations"}) {
        auto it = doc.find(section);
        if (it != doc.end() && it->is_object()) return true;
    }
    auto scene = doc.find("scene");
    return scene != doc.end() && scene->is_string();
}

}  // namespace

const std::vector<std::string>& supported_extensions() {
    static const std::vector<std::string> k = {
        "EXT_meshopt_compression",    "KHR_draco_mesh_compression",      "KHR_lights_punctual",
        "KHR_materials_clearcoat",    "KHR_materials_emissive_strength", "KHR_materials_ior",
        "KHR_materials_transmission", "KHR_mesh_quantization",           "KHR_texture_transform"};
    return k;
}

const std::vector<std::string>& look_only_extensions() {
    static const std::vector<std::string> k = {
        "KHR_technique_webgl", "KHR_materials_pbrSpecularGlossiness", "KHR_materials_unlit",
        "KHR_materials_sheen", "KHR_materials_specular",
        "KHR_materials_volume", "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_dispersion",
        "KHR_materials_variants"};
    return k;
}

std::vector<std::string> refuse_unsupported(const std::string& version, const std::vector<std::string>& required,
                                            const std::string& file) {
    if (is_version_1(version)) refuse_version(version, file);
    auto listed = [](const std::vector<std::string>& list, const std::string& name) {
        for (const auto& s : list)
            if (s == name) return true;
        return false;
    };
    std::vector<std::string> warnings;
    std::string missing;
    std::size_t count = 0;
    for (const auto& name : required) {
        if (listed(supported_extensions(), name)) continue;
        if (listed(look_only_extensions(), name)) {
            warnings.push_back(file + ": extensionsRequired: " + name +
                               " is not implemented; rendered with the core glTF 2.0 materials, so the look may differ");
            continue;
        }
        missing += (missing.empty() ? "" : ", ") + name;
        ++count;
    }
    if (missing.empty()) return warnings;
    std::string have;
    for (const auto& s : supported_extensions()) have += (have.empty() ? "" : ", ") + s;
    throw Error(file + ": extensionsRequired: " + missing + (count == 1 ? " is" : " are") +
                " not supported: the file cannot be read without " + (count == 1 ? "it" : "them") +
                " (clpath implements " + have + ")");
}

void refuse_version_1_structure(const nlohmann::json& doc, const std::string& file) {
    if (has_version_1_structure(doc)) refuse_version("1.0", file);
}

std::string incomplete_triangle_warning(const std::string& file, const std::string& path, std::size_t corners) {
    const std::size_t extra = corners % 3;
    return file + ": " + path + ": " + std::to_string(corners) + " corners are not a whole number of triangles; the last " +
           std::to_string(extra) + (extra == 1 ? " is" : " are") + " dropped";
}

std::string points_and_lines_warning(const std::string& file, const std::string& path) {
    return file + ": " + path + ".mode: points and lines cannot be rendered (clpath renders triangles); skipped";
}

}  // namespace clpath::gltf
