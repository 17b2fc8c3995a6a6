#include "scene/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace clpath {

std::vector<glm::vec3> make_plane() {
    const glm::vec3 a(-0.5f, 0, -0.5f), b(-0.5f, 0, 0.5f), c(0.5f, 0, 0.5f), d(0.5f, 0, -0.5f);
    return {a, b, c, a, c, d};
}

std::vector<glm::vec3> make_box() {
    // Each face: the plane turned to face along one axis, pushed out by 0.5.
    std::vector<glm::vec3> out;
    const std::array<std::pair<glm::vec3, glm::vec3>, 6> faces = {{
        {{0, 0.5f, 0}, {0, 0, 0}},
        {{0, -0.5f, 0}, {glm::pi<float>(), 0, 0}},
        {{0.5f, 0, 0}, {0, 0, -glm::half_pi<float>()}},
        {{-0.5f, 0, 0}, {0, 0, glm::half_pi<float>()}},
        {{0, 0, 0.5f}, {glm::half_pi<float>(), 0, 0}},
        {{0, 0, -0.5f}, {-glm::half_pi<float>(), 0, 0}},
    }};
    for (const auto& [pos, rot] : faces) {
        auto f = transformed(make_plane(), shape_transform(pos, rot, glm::vec3(1)));
        // Rotations leave float dust (cos(pi/2) != 0): snap to the exact cube.
        for (auto& v : f) v = glm::round(v * 2.0f) * 0.5f;
        out.insert(out.end(), f.begin(), f.end());
    }
    return out;
}

std::vector<glm::vec3> make_icosphere(int iterations) {
    if (iterations < 0 || iterations > 10)
        throw std::invalid_argument("icosphere subdivision level must be in [0, 10], got " +
                                    std::to_string(iterations));
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int it = 0; it < iterations; ++it) {
        // Shared midpoints, so the mesh stays closed (watertight) after splitting.
        std::map<std::pair<unsigned, unsigned>, unsigned> mid;
        auto midpoint = [&](unsigned a, unsigned b) {
            auto key = std::minmax(a, b);
            auto [it2, fresh] = mid.try_emplace({key.first, key.second}, unsigned(v.size()));
            if (fresh) v.push_back(glm::normalize(v[a] + v[b]));
            return it2->second;
        };
        std::vector<glm::uvec3> g;
        g.reserve(f.size() * 4);
        for (auto tri : f) {
            unsigned a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
            g.push_back({tri.x, a, c});
            g.push_back({tri.y, b, a});
            g.push_back({tri.z, c, b});
            g.push_back({a, b, c});
        }
        f.swap(g);
    }
    std::vector<glm::vec3> out;
    out.reserve(f.size() * 3);
    for (auto tri : f) {
        out.push_back(v[tri.x]);
        out.push_back(v[tri.y]);
        out.push_back(v[tri.z]);
    }
    return out;
}

glm::mat4 shape_transform(glm::vec3 position, glm::vec3 rotation, glm::vec3 scale) {
    glm::mat4 m = glm::translate(glm::mat4(1), position);
    m = glm::rotate(m, rotation.x, glm::vec3(1, 0, 0));
    m = glm::rotate(m, rotation.y, glm::vec3(0, 1, 0));
    m = glm::rotate(m, rotation.z, glm::vec3(0, 0, 1));
    return glm::scale(m, scale);
}

std::vector<glm::vec3> transformed(const std::vector<glm::vec3>& tris, const glm::mat4& m) {
    std::vector<glm::vec3> out(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) out[i] = glm::vec3(m * glm::vec4(tris[i], 1.0f));
    if (glm::determinant(glm::mat3(m)) < 0)
        for (std::size_t i = 0; i + 2 < out.size(); i += 3) std::swap(out[i + 1], out[i + 2]);
    return out;
}

}  // namespace clpath
