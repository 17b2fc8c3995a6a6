#include "bvh/instances.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <limits>

#include "bvh/wide.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Rows (m00 m01 m02 t0, ...) of an affine map given column-major.
void store_rows(float* rows, const glm::dmat4& m) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) rows[4 * r + c] = float(m[c][r]);
}

// The world box of an object box under m: its eight corners mapped, then
// widened by a few float roundings of its magnitude, so that a ray the
// kernel moves into object space (its own roundings) cannot miss an
// instance whose object it hits by grazing the box's exact face.
void world_box(const glm::dmat4& m, glm::vec3 lo, glm::vec3 hi, glm::vec3& wlo, glm::vec3& whi) {
    glm::dvec3 a(INFINITY), b(-INFINITY);
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        const glm::dvec3 w(m * glm::dvec4(c, 1.0));
        a = glm::min(a, w);
        b = glm::max(b, w);
    }
    const double mag = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z), std::abs(b.x), std::abs(b.y),
                                 std::abs(b.z), glm::length(b - a)});
    const double pad = mag * 0x1p-20;  // some 16 float ulps of the box's magnitude
    wlo = glm::vec3(a - pad);
    whi = glm::vec3(b + pad);
}

}  // namespace

Instance instance_record(const glm::mat4& object_to_world, const std::string& what) {
    const glm::dmat4 m(object_to_world);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) throw Error(what + ": the transform has a non-finite entry");
    if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1)
        throw Error(what + ": the transform is not affine (its last row must be 0 0 0 1)");
    const glm::dmat3 l(m);
    const double det = glm::determinant(l);
    // Relative to the columns' lengths (Hadamard: |det| <= their product), so
    // a uniformly tiny or huge scale is not singular, collapsed axes are.
    const double scale = glm::length(l[0]) * glm::length(l[1]) * glm::length(l[2]);
    if (!(std::abs(det) > 1e-9 * scale) || !(scale > 0) || !std::isfinite(det))
        throw Error(what + ": the transform is singular (determinant " + std::to_string(det) +
                    "): it flattens the mesh, and no ray could be moved into its object space");
    const glm::dmat4 inv = glm::inverse(m);
    Instance rec{};
    store_rows(rec.object_to_world, m);
    store_rows(rec.world_to_object, inv);
    for (float v : rec.world_to_object)
        if (!std::isfinite(v)) throw Error(what + ": the transform's inverse is not finite in float");
    rec.det_sign = det < 0 ? -1.0f : 1.0f;
    return rec;
}

TwoLevelBvh build_two_level(const std::vector<const std::vector<glm::vec3>*>& meshes,
                            const std::vector<std::uint32_t>& first_prim, const std::vector<InstanceInput>& instances,
                            const BvhBuildOptions& options) {
    if (instances.empty()) throw Error("two-level BVH: no instances");
    if (first_prim.size() != meshes.size()) throw Error("internal: two-level BVH: a first triangle per mesh is needed");
    TwoLevelBvh out;
    out.stats.meshes = meshes.size();
    out.stats.instances = instances.size();

    // Bottom levels, each widened and its boxes kept for the instances' world boxes.
    auto t0 = std::chrono::steady_clock::now();
    std::vector<std::vector<Bvh4Node128>> bottom(meshes.size());
    std::vector<std::uint32_t> first_tri(meshes.size());
    std::vector<glm::vec3> mesh_lo(meshes.size()), mesh_hi(meshes.size());
    std::vector<bool> used(meshes.size(), false);
    for (const auto& in : instances) {
        if (in.mesh >= meshes.size())
            throw Error("two-level BVH: an instance names mesh " + std::to_string(in.mesh) + " of " +
                        std::to_string(meshes.size()));
        used[in.mesh] = true;
    }
    out.mesh_stats.resize(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        if (!used[m]) continue;  // nothing places it: no tree
        Bvh b = build_bvh(*meshes[m], options);
        out.mesh_stats[m] = b.stats;
        bottom[m] = widen_bvh(b.nodes);
        out.stats.bottom_depth = std::max(out.stats.bottom_depth, check_wide(bottom[m], b));
        first_tri[m] = std::uint32_t(out.triangles.size());
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const auto& v : *meshes[m]) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        mesh_lo[m] = lo;
        mesh_hi[m] = hi;
        for (auto& t : b.triangles) {
            t.prim += first_prim[m];
            t.light = CLP_NO_LIGHT;
            out.triangles.push_back(t);
        }
    }
    out.stats.bottom_build_ms = ms_since(t0);

    // The top level: a build over one stand-in triangle per instance whose
    // bounds are the instance's world box (two corners and the first again),
    // one instance per leaf.
    t0 = std::chrono::steady_clock::now();
    std::vector<Instance> records(instances.size());
    std::vector<glm::vec3> boxes(3 * instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) {
        records[i] = instance_record(instances[i].object_to_world, "instance " + std::to_string(i));
        records[i].mesh = instances[i].mesh;
        records[i].first_tri = first_tri[instances[i].mesh];
        records[i].first_prim = first_prim[instances[i].mesh];
        glm::vec3 lo, hi;
        world_box(glm::dmat4(instances[i].object_to_world), mesh_lo[instances[i].mesh], mesh_hi[instances[i].mesh], lo,
                  hi);
        if (!std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z))
            throw Error("instance " + std::to_string(i) + ": its transform places mesh " +
                        std::to_string(instances[i].mesh) + " beyond the float range (its world box is not finite)");
        boxes[3 * i] = lo;
        boxes[3 * i + 1] = hi;
        boxes[3 * i + 2] = lo;
    }
    BvhBuildOptions top_options = options;
    top_options.max_leaf_size = 1;
    const Bvh top = build_bvh(boxes, top_options);
    // The walk's one stack holds the top level's pending siblings under the
    // bottom level's (kernels/shared_structs.h, CLP_INSTANCE_MAX_DEPTH4), so
    // the two 4-wide depths are bounded together. Where the top level's
    // first widening would pass the bound, the widening that takes two
    // binary levels per wide one may still bring it within.
    const int top_room = CLP_INSTANCE_MAX_DEPTH4 - out.stats.bottom_depth;
    std::vector<Bvh4Node128> top_wide = widen_bvh(top.nodes);
    out.stats.top_depth = check_wide(top_wide, top);
    if (out.stats.top_depth > top_room) {
        top_wide = widen_bvh(top.nodes, WideningRule::TwoLevels);
        out.stats.top_depth = check_wide(top_wide, top);
    }
    if (out.stats.top_depth > top_room)
        throw Error("two-level BVH: the top level over " + std::to_string(instances.size()) + " instances is " +
                    std::to_string(out.stats.top_depth) + " 4-wide levels deep and the deepest placed mesh's " +
                    std::to_string(out.stats.bottom_depth) + ", together more than the " +
                    std::to_string(CLP_INSTANCE_MAX_DEPTH4) +
                    " the instanced walk's stack holds; place fewer instances, or flatten the scene");

    std::size_t total = top_wide.size() + records.size();
    std::vector<std::size_t> root(meshes.size(), 0);
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        root[m] = total;
        total += bottom[m].size();
    }
    if (total >= std::size_t(CLP_BVH4_MAX_NODES))
        throw Error("two-level BVH: " + std::to_string(total) + " nodes, more than the kernels address (" +
                    std::to_string(CLP_BVH4_MAX_NODES) + ")");
    out.nodes.reserve(total);
    const int records_at = int(top_wide.size());
    for (auto n : top_wide) {
        for (int s = 0; s < 4; ++s) {
            if (n.child[s] >= 0) continue;
            if (n.count[s] != 1) throw Error("internal: a top-level leaf holds " + std::to_string(n.count[s]) + " instances");
            n.child[s] = ~(records_at + int(top.triangles[std::size_t(~n.child[s])].prim));
            n.count[s] = 1;
        }
        out.nodes.push_back(n);
    }
    out.stats.top_build_ms = ms_since(t0);
    for (auto& r : records) {
        r.blas_root = std::uint32_t(root[r.mesh]);
        Bvh4Node128 slot;
        static_assert(sizeof slot == sizeof r);
        std::memcpy(&slot, &r, sizeof r);
        out.nodes.push_back(slot);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (auto n : bottom[m]) {
            for (int s = 0; s < 4; ++s) {
                if (n.child[s] > 0) n.child[s] += int(root[m]);
                else if (n.child[s] < 0) n.child[s] = ~(~n.child[s] + int(first_tri[m]));
            }
            out.nodes.push_back(n);
        }
    out.stats.top_nodes = top_wide.size();
    out.stats.top_bytes = (top_wide.size() + records.size()) * sizeof(Bvh4Node128);
    out.stats.bottom_bytes = (total - top_wide.size() - records.size()) * sizeof(Bvh4Node128) +
                             out.triangles.size() * sizeof(TriVerts);
    for (const auto& in : instances) out.stats.placed_triangles += meshes[in.mesh]->size() / 3;
    return out;
}

std::string describe(const TwoLevelStats& s) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "two-level BVH: %zu instances of %zu meshes (%zu triangles placed); top level %.2f MB (%zu nodes, "
                  "depth %d) built in %.1f ms; bottom levels %.2f MB built in %.1f ms",
                  s.instances, s.meshes, s.placed_triangles, double(s.top_bytes) / 1e6, s.top_nodes, s.top_depth,
                  s.top_build_ms, double(s.bottom_bytes) / 1e6, s.bottom_build_ms);
    return buf;
}

}  // namespace clpath
