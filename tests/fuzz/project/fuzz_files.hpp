#pragma once
// The files a fuzzed scene may name, held in memory: the fuzzer explores the
// parsers, not the disk (a scene naming /dev/zero would only test patience).
#include <map>
#include <string>

#include "scene/load/load_options.hpp"
#include "scene/scene.hpp"
#include "util/error.hpp"

namespace clpath::fuzz {

// What the renderer relies on of any scene a loader returns; a breach is a finding.
inline void check_scene(const Scene& s) {
    if (s.vertices.size() != s.triangle_count() * 3) __builtin_trap();
    if (!s.normals.empty() && s.normals.size() != s.vertices.size()) __builtin_trap();
    if (!s.uvs.empty() && s.uvs.size() != s.vertices.size()) __builtin_trap();
    if (!s.tangents.empty() && s.tangents.size() != s.vertices.size()) __builtin_trap();
    if (!s.colors.empty() && s.colors.size() != s.vertices.size()) __builtin_trap();
    for (const auto& m : s.materials)
        for (int t : m.texture)
            if (t != CLP_NO_TEXTURE && (t < 0 || std::size_t(t) >= s.textures.size())) __builtin_trap();
    for (auto m : s.triangle_material)
        if (m >= s.materials.size()) __builtin_trap();
    (void)camera_data(s.camera);  // throws clpath::Error for a bad camera, never crashes
}

inline const std::map<std::string, std::string>& files() {
    static const std::map<std::string, std::string> f = {
        {"fuzz/mesh.obj",
         "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nusemtl red\nf 1//1 2//1 3//1 4//1\n"
         "usemtl other\nf 1 3 2\n"},
        {"fuzz/mesh.mtl", "newmtl red\nKd 0.8 0.1 0.1\nnewmtl lamp\nKe 5 5 5\n"},
        {"fuzz/sky.exr", ""},
        // For glTF inputs: one quad (4 positions, 6 uint16 indices), and a 2x1 texture.
        {"fuzz/model.bin", std::string("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0"
                                       "\0\0\x80\x3f\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0"
                                       "\0\0\x01\0\x02\0\0\0\x02\0\x03\0", 60)},
        {"fuzz/texture.rgba", std::string("RGBA\x02\x01\xff\0\0\xff\0\xff\0\x80", 14)},
    };
    return f;
}

inline LoadOptions options() {
    LoadOptions o;
    o.read_file = [](const std::string& path) {
        auto it = files().find(path);
        if (it == files().end()) throw Error(path + ": no such file");
        return it->second;
    };
    o.file_exists = [](const std::string& path) { return files().count(path) > 0; };
    // Enough for every shape kind, small enough that each input runs in milliseconds.
    o.max_triangles = 20000;
    o.max_placed_nodes = 20000;
    return o;
}

}  // namespace clpath::fuzz
