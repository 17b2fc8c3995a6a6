#include "scene/load/scene_loader.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/builtin_scenes.hpp"
#include "scene/load/gltf_scene.hpp"
#include "scene/load/scene_file.hpp"
#include "util/error.hpp"

namespace clpath {

Scene load_scene(const std::string& spec, const LoadOptions& options) {
    namespace fs = std::filesystem;
    std::string ext = fs::path(spec).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".json") return parse_scene_file(options.read_file(spec), spec, options);
    if (ext == ".obj") return obj_scene(spec, options);
    if (ext == ".gltf" || ext == ".glb") return gltf_scene(spec, options);
    // A file of another kind is named as such, rather than as an unknown built-in.
    std::error_code ec;
    if (spec.find('/') != std::string::npos || fs::exists(spec, ec)) {
        if (fs::is_directory(spec, ec)) throw Error(spec + ": is a folder, not a scene file");
        if (fs::exists(spec, ec))
            throw Error(spec + ": unknown scene file type '" + ext + "' (clpath reads .json scene files, .obj meshes and .gltf/.glb models)");
        throw Error(spec + ": no such file");
    }
    return builtin_scene(spec);
}

}  // namespace clpath
