#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <stdexcept>
#include <thread>

#include "bvh/binned_builder.hpp"
#include "bvh/bvh.hpp"
#include "bvh/fork_join.hpp"
#include "util/error.hpp"

namespace clpath {

Bvh build_bvh(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = vertices.size() / 3;
    if (vertices.size() % 3)
        throw Error("BVH build: " + std::to_string(vertices.size()) + " vertices is not a whole number of triangles");
    if (n == 0) throw Error("BVH build: no triangles");
    if (n > kMaxBvhTriangles)
        throw Error("BVH build: " + std::to_string(n) + " triangles; at most " + std::to_string(kMaxBvhTriangles) +
                    " fit the node layout's 31-bit triangle index");
    BvhBuildOptions opt = options;
    if (opt.bins < 2 || opt.bins > 256)
        throw Error("BVH build: bins must be in [2, 256], got " + std::to_string(opt.bins));
    if (opt.max_leaf_size < 1 || opt.max_leaf_size > 64)
        throw Error("BVH build: the leaf size must be in [1, 64], got " + std::to_string(opt.max_leaf_size));
    if (!(opt.traversal_cost >= 0) || !std::isfinite(opt.traversal_cost))
        throw Error("BVH build: the traversal cost must be finite and >= 0, got " + std::to_string(opt.traversal_cost));
    if (opt.threads <= 0) opt.threads = int(std::max(1u, std::thread::hardware_concurrency()));

    Bvh bvh;
    // The triangles' storage is the builder's second array of records until
    // the triangles are written: its pages are then touched already. A
    // separate array was 32 MiB more fresh memory on room:1003542, and the
    // kernel zeroing fresh pages was a tenth of the build's CPU time.
    bvh.triangles.resize(n);
    static_assert(sizeof(TriVerts) >= sizeof(bvh_build::Ref) &&
                  __STDCPP_DEFAULT_NEW_ALIGNMENT__ >= alignof(bvh_build::Ref));
    void* storage = bvh.triangles.data();
    bvh_build::Ref* scatter = static_cast<bvh_build::Ref*>(storage);
    for (std::size_t i = 0; i < n; ++i) ::new (static_cast<void*>(scatter + i)) bvh_build::Ref;  // no code: trivial
    const bvh_build::Tree tree = bvh_build::build_tree(vertices, opt, bvh.nodes, scatter);
    for (std::size_t i = 0; i < n; ++i) ::new (static_cast<void*>(&bvh.triangles[i])) TriVerts;  // no code either
    const bvh_build::Ref* refs = tree.refs.get();
    // The triangles in leaf order, by all threads, by chunks handed out one
    // at a time, so a thread that starts late holds nobody up.
    constexpr std::size_t kChunk = 1 << 14;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    std::atomic<std::size_t> next_chunk{0};
    bvh_build::fork_join(int(std::min<std::size_t>(std::size_t(opt.threads), chunks)), [&](int) {
        for (std::size_t k; (k = next_chunk.fetch_add(1)) < chunks;) {
            for (std::size_t i = k * kChunk; i < std::min(n, (k + 1) * kChunk); ++i) {
                TriVerts& tv = bvh.triangles[i];
                const std::size_t s = refs[i].prim;
                // A triangle's 36 bytes may straddle two cache lines; 24
                // ahead covers a trip to memory (8 ahead: the pass took
                // 8.7 ms on room:1003542, Xeon, against 7.5).
                if (i + 24 < n) {
                    const char* p = reinterpret_cast<const char*>(&vertices[3 * std::size_t(refs[i + 24].prim)]);
                    __builtin_prefetch(p);
                    __builtin_prefetch(p + 3 * sizeof(glm::vec3) - 1);
                }
                for (int a = 0; a < 3; ++a) {
                    tv.v0[a] = vertices[3 * s][a];
                    tv.v1[a] = vertices[3 * s + 1][a];
                    tv.v2[a] = vertices[3 * s + 2][a];
                }
                tv.prim = std::uint32_t(s);
                tv.light = CLP_NO_LIGHT;  // the renderer marks emitters
                tv.pad2 = 0;
            }
        }
    });
    bvh.nodes.resize(tree.node_count);  // smaller: nothing moves
    bvh.stats.leaf_count = tree.leaf_count;
    bvh.stats.max_depth = tree.max_depth;
    bvh.stats.sah_cost = tree.sah_cost;
    bvh.stats.node_count = bvh.nodes.size();
    bvh.stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return bvh;
}

std::string describe(const BvhStats& s) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "BVH: %zu nodes, %zu leaves, depth %d, SAH cost %.2f, built in %.1f ms",
                  s.node_count, s.leaf_count, s.max_depth, s.sah_cost, s.build_ms);
    return buf;
}

void check_bvh(const Bvh& bvh, std::size_t triangle_count) {
    auto fail = [](const std::string& what) { throw std::logic_error("BVH invariant broken: " + what); };
    if (bvh.nodes.empty()) fail("no root");
    if (bvh.triangles.size() != triangle_count) fail("triangle count differs from the scene's");
    std::vector<int> seen_tri(triangle_count, 0), seen_node(bvh.nodes.size(), 0);
    auto contains = [](const float* lo, const float* hi, const float* p) {
        for (int a = 0; a < 3; ++a)
            if (!(p[a] >= lo[a] && p[a] <= hi[a])) return false;
        return true;
    };
    auto contains_box = [](const float* lo, const float* hi, const float* clo, const float* chi) {
        for (int a = 0; a < 3; ++a)
            if (!(clo[a] >= lo[a] && chi[a] <= hi[a])) return false;
        return true;
    };
    struct Item {
        int node, depth;
    };
    std::vector<Item> stack{{0, 1}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        if (it.depth > CLP_BVH_MAX_DEPTH) fail("depth " + std::to_string(it.depth) + " exceeds the traversal stack");
        if (seen_node[it.node]++) fail("node " + std::to_string(it.node) + " reached twice");
        const BvhNode64& n = bvh.nodes[it.node];
        for (int s = 0; s < 2; ++s) {
            const float* lo = s ? n.lo1 : n.lo0;
            const float* hi = s ? n.hi1 : n.hi0;
            const int child = s ? n.child1 : n.child0;
            const std::uint32_t count = s ? n.count1 : n.count0;
            if (child >= 0) {
                if (std::size_t(child) >= bvh.nodes.size()) fail("child index out of range");
                const BvhNode64& c = bvh.nodes[child];
                if (!contains_box(lo, hi, c.lo0, c.hi0) || !contains_box(lo, hi, c.lo1, c.hi1))
                    fail("node " + std::to_string(child) + "'s box is not inside its parent's slot");
                stack.push_back({child, it.depth + 1});
                continue;
            }
            const std::size_t first = std::size_t(~child);
            if (first + count > bvh.triangles.size()) fail("leaf range out of range");
            for (std::size_t i = first; i < first + count; ++i) {
                const TriVerts& t = bvh.triangles[i];
                if (!contains(lo, hi, t.v0) || !contains(lo, hi, t.v1) || !contains(lo, hi, t.v2))
                    fail("triangle " + std::to_string(t.prim) + " sticks out of its leaf box");
                if (t.prim >= triangle_count) fail("triangle index out of range");
                if (seen_tri[t.prim]++) fail("triangle " + std::to_string(t.prim) + " referenced twice");
            }
        }
    }
    for (std::size_t i = 0; i < triangle_count; ++i)
        if (!seen_tri[i]) fail("triangle " + std::to_string(i) + " not referenced");
    for (std::size_t i = 0; i < seen_node.size(); ++i)
        if (!seen_node[i]) fail("node " + std::to_string(i) + " unreachable");
}

}  // namespace clpath
