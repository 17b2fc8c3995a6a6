// The triangles of the OBJ `clpath export SCENE out/x.json` writes (v lines and
// triangular f lines), three tinybvh vertices per triangle. Shared by the
// side-by-side harnesses (tinybvh_rays.cpp, ../../bvh_build/tinybvh_build.cpp).
// Our code; tinybvh.h must be included first.
#pragma once
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace harness {

inline std::vector<tinybvh::bvhvec4> read_obj_triangles(const std::string& path) {
    using tinybvh::bvhvec4;
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<bvhvec4> v, tris;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        std::istringstream ss(line);
        std::string tag;
        ss >> tag;
        if (tag == "v") {
            float x, y, z;
            if (!(ss >> x >> y >> z)) throw std::runtime_error(path + ":" + std::to_string(n) + ": bad vertex");
            v.push_back(bvhvec4(x, y, z, 0));
        } else if (tag == "f") {
            std::vector<long> idx;
            std::string tok;
            while (ss >> tok) idx.push_back(std::strtol(tok.c_str(), nullptr, 10));  // "a", "a/b", "a//c"
            if (idx.size() != 3) throw std::runtime_error(path + ":" + std::to_string(n) + ": only triangles are read");
            for (long i : idx) {
                if (i < 1 || std::size_t(i) > v.size())
                    throw std::runtime_error(path + ":" + std::to_string(n) + ": vertex index out of range");
                tris.push_back(v[std::size_t(i) - 1]);
            }
        }
    }
    if (tris.empty()) throw std::runtime_error(path + ": no triangles");
    return tris;
}

}  // namespace harness
