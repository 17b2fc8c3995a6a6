#include "scene/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "util/error.hpp"

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
        throw Error("icosphere: the subdivision level must be in [0, 10], got " + std::to_string(iterations));
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

namespace {
constexpr float kTwoPi = 6.28318530717958647692f;

// Indexed to soup, with vertex normals averaged from the faces around each
// vertex (weighted by area, through the unnormalised cross product).
ShapeMesh to_soup(const std::vector<glm::vec3>& pos, const std::vector<glm::uvec3>& faces) {
    std::vector<glm::vec3> vn(pos.size(), glm::vec3(0));
    for (auto f : faces) {
        const glm::vec3 n = glm::cross(pos[f.y] - pos[f.x], pos[f.z] - pos[f.x]);
        vn[f.x] += n;
        vn[f.y] += n;
        vn[f.z] += n;
    }
    for (auto& n : vn) {
        const float l = glm::length(n);
        n = l > 0 ? n / l : glm::vec3(0, 1, 0);
    }
    ShapeMesh m;
    m.vertices.reserve(faces.size() * 3);
    m.normals.reserve(faces.size() * 3);
    for (auto f : faces)
        for (unsigned i : {f.x, f.y, f.z}) {
            m.vertices.push_back(pos[i]);
            m.normals.push_back(vn[i]);
        }
    return m;
}

float sphere_bump(const Bumps& b, glm::vec3 p) {
    switch (b.kind) {
    case Bumps::Kind::Sine:
        return b.amplitude * std::sin(kTwoPi * b.frequency * p.x) * std::sin(kTwoPi * b.frequency * p.y) *
               std::sin(kTwoPi * b.frequency * p.z);
    case Bumps::Kind::Ripple: return b.amplitude * std::cos(kTwoPi * b.frequency * p.y);
    case Bumps::Kind::None: break;
    }
    return 0;
}

float grid_height(const Bumps& b, float x, float z) {
    switch (b.kind) {
    case Bumps::Kind::Sine: return b.amplitude * std::sin(kTwoPi * b.frequency * x) * std::sin(kTwoPi * b.frequency * z);
    case Bumps::Kind::Ripple: return b.amplitude * std::cos(kTwoPi * b.frequency * std::sqrt(x * x + z * z));
    case Bumps::Kind::None: break;
    }
    return 0;
}
}  // namespace

std::pair<int, int> uv_sphere_resolution(std::size_t triangles) {
    // Segments about twice the rings keeps the quads near the equator square.
    const double t = double(std::max<std::size_t>(triangles, 12));
    const int rings = std::max(2, int(std::lround((1.0 + std::sqrt(1.0 + t)) / 2.0)));
    const int segments = std::max(3, int(std::lround(t / (2.0 * (rings - 1)))));
    return {rings, segments};
}

ShapeMesh make_uv_sphere(std::size_t triangles, const Bumps& bumps) {
    // Plain variables, not a structured binding: clang 14 (the fuzz build)
    // cannot capture those in the lambda below.
    const std::pair<int, int> res = uv_sphere_resolution(triangles);
    const int rings = res.first, segments = res.second;
    // Vertex 0 is the north pole, then (rings - 1) latitude circles, then the south pole.
    std::vector<glm::vec3> pos;
    pos.reserve(std::size_t(rings - 1) * segments + 2);
    pos.push_back({0, 1, 0});
    for (int i = 1; i < rings; ++i) {
        const float theta = glm::pi<float>() * float(i) / float(rings);
        for (int j = 0; j < segments; ++j) {
            const float phi = kTwoPi * float(j) / float(segments);
            pos.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
        }
    }
    pos.push_back({0, -1, 0});
    if (bumps.kind != Bumps::Kind::None)
        for (auto& p : pos) p *= 1.0f + sphere_bump(bumps, p);
    const unsigned south = unsigned(pos.size() - 1);
    auto ring = [&](int i, int j) { return unsigned(1 + (i - 1) * segments + (j % segments)); };
    std::vector<glm::uvec3> faces;
    faces.reserve(std::size_t(2) * segments * (rings - 1));
    // Seen from outside, going around +y counter-clockwise means decreasing phi
    // (phi turns from +x towards +z, i.e. clockwise seen from above).
    for (int j = 0; j < segments; ++j) faces.push_back({0, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            faces.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
            faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
        }
    for (int j = 0; j < segments; ++j) faces.push_back({south, ring(rings - 1, j), ring(rings - 1, j + 1)});
    ShapeMesh m = to_soup(pos, faces);
    if (bumps.kind == Bumps::Kind::None)
        for (std::size_t i = 0; i < m.vertices.size(); ++i) m.normals[i] = m.vertices[i];
    return m;
}

ShapeMesh make_grid(int nx, int nz, const Bumps& height) {
    if (nx < 1 || nz < 1)
        throw Error("grid: the resolution must be at least 1 x 1 cells, got " + std::to_string(nx) + " x " +
                    std::to_string(nz));
    std::vector<glm::vec3> pos;
    pos.reserve(std::size_t(nx + 1) * (nz + 1));
    for (int i = 0; i <= nx; ++i)
        for (int k = 0; k <= nz; ++k) {
            const float x = float(i) / float(nx) - 0.5f, z = float(k) / float(nz) - 0.5f;
            pos.push_back({x, grid_height(height, x, z), z});
        }
    auto at = [&](int i, int k) { return unsigned(i * (nz + 1) + k); };
    std::vector<glm::uvec3> faces;
    faces.reserve(std::size_t(2) * nx * nz);
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k) {
            // The plane's corner order (a b c, a c d), so a flat grid faces +y like it.
            faces.push_back({at(i, k), at(i, k + 1), at(i + 1, k + 1)});
            faces.push_back({at(i, k), at(i + 1, k + 1), at(i + 1, k)});
        }
    return to_soup(pos, faces);
}

ShapeMesh make_smooth_icosphere(int iterations) {
    ShapeMesh m;
    m.vertices = make_icosphere(iterations);
    m.normals = m.vertices;  // on the unit sphere, position is the normal
    return m;
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
