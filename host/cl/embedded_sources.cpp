#include "cl/embedded_sources.hpp"

#include <map>

#include "util/error.hpp"

namespace clpath {

const std::string& embedded_source(const std::string& name) {
    static const std::map<std::string, std::string> by_name = [] {
        std::map<std::string, std::string> m;
        for (const auto& s : embedded_sources()) m.emplace(s.name, s.text);
        return m;
    }();
    auto it = by_name.find(name);
    if (it == by_name.end()) throw Error("internal: no embedded kernel source named " + name);
    return it->second;
}

std::string program_source(const std::vector<std::string>& files) {
    std::string src = embedded_source("shared_structs.h");
    for (const auto& f : files) {
        // #line keeps compiler messages pointing at the right file and line.
        src += "\n#line 1 \"" + f + "\"\n";
        src += embedded_source(f);
    }
    return src;
}

const std::vector<std::string>& renderer_kernel_files() {
    static const std::vector<std::string> files = {
        "rng.cl", "sampling.cl", "camera.cl", "intersect.cl", "textures.cl", "traverse.cl",
        "materials.cl", "material_gltf.cl", "surface_params.cl", "lights.cl", "film.cl", "integrator.cl"};
    return files;
}

}  // namespace clpath
