#include "scene/load/polygon_triangulation.hpp"

#include <cmath>

namespace clpath {
namespace {

using Tri = std::array<std::size_t, 3>;

std::vector<Tri> fan(std::size_t n) {
    std::vector<Tri> out;
    for (std::size_t k = 1; k + 1 < n; ++k) out.push_back({0, k, k + 1});
    return out;
}

double cross2(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

// p inside or on the boundary of the counter-clockwise triangle abc.
bool in_triangle(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

}  // namespace

std::vector<Tri> triangulate_polygon(const std::vector<glm::vec3>& corners) {
    const std::size_t n0 = corners.size();
    if (n0 < 3) return {};
    if (n0 == 3) return {Tri{0, 1, 2}};

    // The corners left after dropping repeats of the one before (cyclically).
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < n0; ++i)
        if (idx.empty() || corners[i] != corners[idx.back()]) idx.push_back(i);
    while (idx.size() > 1 && corners[idx.back()] == corners[idx.front()]) idx.pop_back();
    if (idx.size() < 3) return fan(n0);
    // An outline gone round more than once ("f 1 2 3 4 1 2 3 4 ...", as in
    // assimp's box_longline.obj) is the face once: ear clipping would lay
    // copies over it, some of them turned over.
    for (std::size_t period = 3; period * 2 <= idx.size(); ++period) {
        if (idx.size() % period) continue;
        bool repeats = true;
        for (std::size_t i = period; i < idx.size() && repeats; ++i) repeats = corners[idx[i]] == corners[idx[i - period]];
        if (repeats) {
            idx.resize(period);
            break;
        }
    }

    // Newell's method: the area-weighted normal, sound for concave and
    // slightly non-planar polygons alike. In double: corners may be far from
    // the origin.
    glm::dvec3 normal(0);
    for (std::size_t i = 0; i < idx.size(); ++i) {
        const glm::dvec3 a = corners[idx[i]], b = corners[idx[(i + 1) % idx.size()]];
        normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    const double len = glm::length(normal);
    if (!(len > 0) || !std::isfinite(len)) return fan(n0);
    normal /= len;
    // A right-handed basis (u, v, normal): the polygon, wound counter-clockwise
    // about its normal, is counter-clockwise in (u, v).
    const glm::dvec3 helper = std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, normal)), v = glm::cross(normal, u);
    std::vector<glm::dvec2> p(n0);
    const glm::dvec3 origin = corners[idx[0]];
    for (std::size_t i : idx) {
        const glm::dvec3 d = glm::dvec3(corners[i]) - origin;
        p[i] = {glm::dot(d, u), glm::dot(d, v)};
    }

    // Ear clipping (Meisters 1975; as in Eberly, "Triangulation by Ear
    // Clipping"): a convex corner whose triangle holds no other corner is cut
    // off, until three are left. O(n^2) per ear at worst, fine for faces.
    std::vector<Tri> out;
    std::vector<std::size_t> ring = idx;
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        std::size_t cut = m;  // none found yet
        for (std::size_t k = 0; k < m && cut == m; ++k) {
            const std::size_t a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
            if (cross2(p[a], p[b], p[c]) <= 0) continue;  // reflex or flat: not an ear
            bool empty = true;
            for (std::size_t j = 0; j < m && empty; ++j) {
                const std::size_t q = ring[j];
                if (q == a || q == b || q == c) continue;
                if (p[q] == p[a] || p[q] == p[b] || p[q] == p[c]) continue;  // a corner touching itself
                empty = !in_triangle(p[q], p[a], p[b], p[c]);
            }
            if (empty) cut = k;
        }
        // A self-intersecting or numerically flat outline can have no ear:
        // the least bad cut is a convex corner, else any (the result then
        // overlaps, as the input does).
        if (cut == m)
            for (std::size_t k = 0; k < m && cut == m; ++k)
                if (cross2(p[ring[(k + m - 1) % m]], p[ring[k]], p[ring[(k + 1) % m]]) > 0) cut = k;
        if (cut == m) cut = 0;
        out.push_back({ring[(cut + m - 1) % m], ring[cut], ring[(cut + 1) % m]});
        ring.erase(ring.begin() + std::ptrdiff_t(cut));
    }
    out.push_back({ring[0], ring[1], ring[2]});
    return out;
}

}  // namespace clpath
