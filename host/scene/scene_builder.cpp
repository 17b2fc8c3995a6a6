#include "scene/scene_builder.hpp"

#include <algorithm>
#include <cmath>

#include "util/error.hpp"

namespace clpath {

glm::vec3 flat_normal(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2) {
    const glm::vec3 n = glm::cross(v1 - v0, v2 - v0);
    const float l = glm::length(n);
    return l > 0 && std::isfinite(l) ? n / l : glm::vec3(0, 1, 0);
}

bool is_degenerate(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2) {
    for (const glm::vec3& v : {v0, v1, v2})
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return true;
    // In double, relative to the longest edge: a sliver whose area is lost in
    // float rounding can never be hit, and its normal is noise.
    const glm::dvec3 a(v0), b(v1), c(v2);
    const glm::dvec3 e1 = b - a, e2 = c - a, e3 = c - b;
    const double longest = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
    const double area2 = glm::length(glm::cross(e1, e2));
    return !(area2 > 1e-10 * longest) || !std::isfinite(area2);
}

void SceneBuilder::reserve(std::size_t triangles, const std::string& label) const {
    const std::size_t have = scene_.triangle_count();
    if (triangles > max_triangles_ || have + triangles > max_triangles_)
        throw Error(label + ": " + std::to_string(triangles) + " more triangles would exceed the limit of " +
                    std::to_string(max_triangles_) + " for one scene");
}

void SceneBuilder::add(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                       const glm::mat4& m, const std::vector<std::uint32_t>& materials, const std::string& label,
                       const VertexAttributes& attributes) {
    const std::size_t n = vertices.size() / 3;
    reserve(n, label);
    const glm::mat3 l(m);
    const float det = glm::determinant(l);
    // A mirroring transform turns triangles inside out: swap two corners back.
    const bool flip = det < 0;
    // Normals go through the cofactor matrix (columns c1 x c2, c2 x c0, c0 x c1),
    // the inverse transpose times the determinant: the same direction up to
    // the determinant's sign, and defined even for a flattening scale.
    const glm::mat3 cofactor(glm::cross(l[1], l[2]), glm::cross(l[2], l[0]), glm::cross(l[0], l[1]));
    const glm::mat3 normal_m = cofactor * (flip ? -1.0f : 1.0f);

    const bool smooth = !normals.empty();
    if (smooth && !with_normals_) {
        // The first smooth object: every triangle so far gets its flat normal.
        scene_.normals.reserve(scene_.vertices.size() + vertices.size());
        for (std::size_t t = 0; t < scene_.triangle_count(); ++t) {
            const glm::vec3 f = flat_normal(scene_.vertices[3 * t], scene_.vertices[3 * t + 1], scene_.vertices[3 * t + 2]);
            scene_.normals.insert(scene_.normals.end(), {f, f, f});
        }
        with_normals_ = true;
    }
    // Attributes stay empty or complete: the first object that has one fills
    // it in for everything before it, and later objects without it get the default.
    auto given = [&](const auto* v) { return v && !v->empty(); };
    auto start = [&](auto& dst, const auto* src, auto fallback, bool& active) {
        if (given(src) && !active) {
            dst.assign(scene_.vertices.size(), fallback);
            active = true;
        }
        if (active) dst.reserve(dst.size() + vertices.size());
    };
    const glm::vec2 no_uv(0);
    const glm::vec4 no_tangent(0), white(1);
    start(scene_.uvs, attributes.uvs, no_uv, with_uvs_);
    start(scene_.tangents, attributes.tangents, no_tangent, with_tangents_);
    start(scene_.colors, attributes.colors, white, with_colors_);
    scene_.vertices.reserve(scene_.vertices.size() + vertices.size());
    scene_.triangle_material.reserve(scene_.triangle_material.size() + n);
    if (with_normals_) scene_.normals.reserve(scene_.normals.size() + vertices.size());

    const std::uint32_t object = scene_.next_object_id();
    std::size_t dropped = 0;
    for (std::size_t t = 0; t < n; ++t) {
        glm::vec3 p[3];
        for (int c = 0; c < 3; ++c) p[c] = glm::vec3(m * glm::vec4(vertices[3 * t + c], 1.0f));
        if (is_degenerate(p[0], p[1], p[2])) {
            ++dropped;
            continue;
        }
        const int c1 = flip ? 2 : 1, c2 = flip ? 1 : 2;
        scene_.vertices.insert(scene_.vertices.end(), {p[0], p[c1], p[c2]});
        scene_.triangle_material.push_back(materials.size() == 1 ? materials[0] : materials[t]);
        scene_.triangle_object.push_back(object);
        const int corner[3] = {0, c1, c2};
        for (int c : corner) {
            const std::size_t i = 3 * t + std::size_t(c);
            if (with_uvs_) scene_.uvs.push_back(given(attributes.uvs) ? (*attributes.uvs)[i] : no_uv);
            if (with_colors_) scene_.colors.push_back(given(attributes.colors) ? (*attributes.colors)[i] : white);
            if (with_tangents_) {
                scene_.tangents.push_back(given(attributes.tangents) ? moved_tangent(l, flip, (*attributes.tangents)[i])
                                                                     : no_tangent);
            }
        }
        if (!with_normals_) continue;
        // The flat normal only where no usable smooth one is given (it costs a square root per triangle).
        glm::vec3 out[3];
        bool ok = smooth;
        if (smooth) {
            glm::vec3 sn[3];
            for (int c = 0; c < 3 && ok; ++c) {
                const glm::vec3 v = normal_m * normals[3 * t + c];
                const float len = glm::length(v);
                ok = len > 0 && std::isfinite(len);
                sn[c] = v / len;
            }
            if (ok) {
                out[0] = sn[0];
                out[1] = sn[c1];
                out[2] = sn[c2];
            }
        }
        if (!ok) out[0] = out[1] = out[2] = flat_normal(p[0], p[c1], p[c2]);
        scene_.normals.insert(scene_.normals.end(), {out[0], out[1], out[2]});
    }
    if (dropped) {
        dropped_total_ += dropped;
        dropped_.emplace_back(label, dropped);
    }
}

void SceneBuilder::finish() {
    if (!dropped_total_) return;
    std::string where;
    for (const auto& [label, count] : dropped_) where += (where.empty() ? "" : "; ") + label + ": " + std::to_string(count);
    scene_.warnings.push_back("dropped " + std::to_string(dropped_total_) + " degenerate triangle" +
                              (dropped_total_ == 1 ? "" : "s") + " (zero area or non-finite vertices): " + where);
}

}  // namespace clpath
