#include "scene/load/scene_instances.hpp"

#include <cmath>

#include "scene/shapes.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

using jsonf::Object;
using jsonf::Value;

// The reason an affine map cannot place an instance, or empty: every entry
// finite, and det not negligible against the columns' lengths (Hadamard:
// |det| <= their product), so a tiny uniform scale passes and a collapsed
// axis does not. The renderer moves rays into object space by the inverse.
std::string unusable(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return "the transform has a non-finite entry";
    const glm::dmat3 l{glm::mat3(m)};
    const double det = glm::determinant(l);
    const double scale = glm::length(l[0]) * glm::length(l[1]) * glm::length(l[2]);
    if (!(std::abs(det) > 1e-9 * scale) || !(scale > 0))
        return "the transform is singular (determinant " + std::to_string(det) +
               "): it flattens the mesh, and an instance needs an invertible map";
    const glm::mat4 inv = glm::inverse(m);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(inv[c][r])) return "the transform's inverse is not finite in float";
    return "";
}

glm::mat4 read_matrix(const Value& v) {
    const auto a = v.array();
    if (a.size() != 12 && a.size() != 16)
        v.fail("expected 12 or 16 numbers (a 3x4 or 4x4 matrix, row by row), got " + std::to_string(a.size()));
    glm::mat4 m(1.0f);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = a[std::size_t(4 * r + c)].real();
    if (a.size() == 16) {
        const float last[4] = {a[12].real(), a[13].real(), a[14].real(), a[15].real()};
        if (last[0] != 0 || last[1] != 0 || last[2] != 0 || last[3] != 1)
            v.fail("the last row must be 0 0 0 1 (an affine map)");
    }
    return m;
}

}  // namespace

std::vector<glm::mat4> read_instance_transforms(const Value& list) {
    const auto entries = list.array();
    if (entries.empty()) list.fail("an instances list needs at least one entry");
    std::vector<glm::mat4> out;
    out.reserve(entries.size());
    for (const auto& e : entries) {
        Object o(e);
        const auto matrix = o.get("matrix");
        const auto t = o.get("translate");
        const auto r = o.get("rotate");
        const auto s = o.get("scale");
        o.finish();
        glm::mat4 m(1.0f);
        if (matrix) {
            for (const auto& other : {t, r, s})
                if (other) other->fail("give either matrix or translate/rotate/scale, not both");
            m = read_matrix(*matrix);
        } else {
            const glm::vec3 tv = t ? t->vec3() : glm::vec3(0);
            const glm::vec3 rv = r ? r->vec3(jsonf::Range{-36000, 36000}) : glm::vec3(0);
            const glm::vec3 sv = s ? s->scalar_or_vec3(jsonf::kAny) : glm::vec3(1);
            m = shape_transform(tv, glm::radians(rv), sv);
        }
        const std::string why = unusable(m);
        if (!why.empty()) {
            if (matrix) matrix->fail(why);
            if (s) s->fail(why);
            e.fail(why);
        }
        out.push_back(m);
    }
    return out;
}

std::string flattened_because(const Scene& scene, const std::vector<std::uint32_t>& materials) {
    for (auto m : materials)
        if (emits(scene.materials[m])) return "the mesh emits, and the light table lists flattened emitters only";
    return "";
}

void place_mesh_instances(Scene& scene, SceneBuilder& builder, const std::string& label,
                          const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                          const std::vector<std::uint32_t>& materials, const glm::mat4& place,
                          const std::vector<glm::mat4>& transforms, const VertexAttributes& attributes) {
    // A mesh placed once costs the two-level walk more than it saves: on
    // bunnies:1 it traced 0.62-0.66x the rays per second of the one-level
    // BVH over the same triangles (PoCL, benchmarks/results/pocl-epyc-2core/
    // instancing), so such a mesh is placed as the flat scene places it.
    std::string because = flattened_because(scene, materials);
    if (because.empty() && transforms.size() == 1) because = "a mesh placed once is walked faster in the one-level BVH";
    if (!because.empty()) {
        scene.notes.push_back(label + ": " + std::to_string(transforms.size()) +
                              (transforms.size() == 1 ? " copy" : " copies") + " placed flattened, not instanced (" +
                              because + ")");
        for (const auto& t : transforms) builder.add(vertices, normals, t * place, materials, label, attributes);
        return;
    }
    const std::string why = unusable(place);
    if (!why.empty()) throw Error(label + ": transform: " + why);
    // The mesh in the space the instances place: `place` applied as
    // SceneBuilder applies a transform (mirroring swaps two corners back,
    // normals go through the inverse transpose, tangents move with it), so a
    // copy under the identity is the flattened object, triangle for triangle.
    const glm::mat3 l(place);
    const bool flip = glm::determinant(l) < 0;
    const glm::mat3 normal_m = glm::transpose(glm::inverse(l));
    auto given = [](const auto* v) { return v && !v->empty(); };
    InstancedMesh mesh;
    mesh.name = label;
    const std::size_t n = vertices.size() / 3;
    builder.reserve(n, label);
    std::size_t dropped = 0;
    for (std::size_t t = 0; t < n; ++t) {
        glm::vec3 p[3];
        for (int c = 0; c < 3; ++c) p[c] = glm::vec3(place * glm::vec4(vertices[3 * t + c], 1.0f));
        if (is_degenerate(p[0], p[1], p[2])) {
            ++dropped;
            continue;
        }
        const int corner[3] = {0, flip ? 2 : 1, flip ? 1 : 2};
        for (int c : corner) mesh.vertices.push_back(p[c]);
        mesh.triangle_material.push_back(materials.size() == 1 ? materials[0] : materials[t]);
        for (int c : corner) {
            const std::size_t i = 3 * t + std::size_t(c);
            if (!normals.empty()) {
                const glm::vec3 nv = normal_m * normals[i];
                const float len = glm::length(nv);
                mesh.normals.push_back(len > 0 && std::isfinite(len) ? nv / len : glm::vec3(0));
            }
            if (given(attributes.uvs)) mesh.uvs.push_back((*attributes.uvs)[i]);
            if (given(attributes.tangents)) mesh.tangents.push_back(moved_tangent(l, flip, (*attributes.tangents)[i]));
            if (given(attributes.colors)) mesh.colors.push_back((*attributes.colors)[i]);
        }
    }
    if (dropped)
        scene.warnings.push_back(label + ": " + std::to_string(dropped) + " degenerate triangles dropped");
    if (mesh.triangle_material.empty()) {
        scene.warnings.push_back(label + ": every triangle of the mesh is degenerate; no instance placed");
        return;
    }
    const std::uint32_t index = std::uint32_t(scene.meshes.size());
    scene.meshes.push_back(std::move(mesh));
    for (const auto& t : transforms) scene.instances.push_back({index, t});
}

}  // namespace clpath
