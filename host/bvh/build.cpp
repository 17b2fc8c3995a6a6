#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <thread>

#include "bvh/binned_builder.hpp"
#include "bvh/bvh.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

using bvh_build::TreeNode;

float node_area(const TreeNode& n) {
    const float ex = n.hi[0] - n.lo[0], ey = n.hi[1] - n.lo[1], ez = n.hi[2] - n.lo[2];
    return 2 * (ex * ey + ey * ez + ez * ex);
}

void set_slot(BvhNode64& node, int slot, const TreeNode& c, int child_index) {
    float* lo = slot == 0 ? node.lo0 : node.lo1;
    float* hi = slot == 0 ? node.hi0 : node.hi1;
    for (int a = 0; a < 3; ++a) {
        lo[a] = c.lo[a];
        hi[a] = c.hi[a];
    }
    const int child = c.count ? ~int(c.link) : child_index;
    (slot == 0 ? node.child0 : node.child1) = child;
    (slot == 0 ? node.count0 : node.count1) = c.count;
}

struct FlatStats {
    double cost = 0;  // SAH, over the root's area
    std::size_t leaves = 0;
    int max_depth = 0;
};

// Depth first from the interior node at slot root, its BvhNode64 at index
// first, the nodes below from first + 1 on (a node's children get their
// indices together, when it is visited). offset_of(slot): the BvhNode64 index
// of a subtree flattened apart, or -1 to descend into it here.
template <class OffsetOf>
int flatten_from(const TreeNode* tree, std::uint32_t root, int depth, int first, BvhNode64* out, float root_area,
                 float traversal_cost, FlatStats& st, OffsetOf offset_of) {
    struct Item {
        std::uint32_t slot;
        int node, depth;
    };
    Item stack[2 * CLP_BVH_MAX_DEPTH + 4];  // grows by at most one per level
    int sp = 0;
    stack[sp++] = {root, first, depth};
    int next = first + 1;
    // Sums in locals: through st, every node's store and reload would chain
    // (st might alias out for all the compiler knows).
    double cost = st.cost;
    std::size_t leaves = st.leaves;
    int max_depth = st.max_depth;
    while (sp > 0) {
        const Item it = stack[--sp];
        const TreeNode& b = tree[it.slot];
        cost += traversal_cost * node_area(b) / root_area;
        max_depth = std::max(max_depth, it.depth);
        const std::uint32_t kids[2] = {it.slot + 1, b.link};
        for (int s = 0; s < 2; ++s) {
            const TreeNode& c = tree[kids[s]];
            int index = 0;
            if (c.count) {
                ++leaves;
                cost += double(c.count) * node_area(c) / root_area;
            } else if ((index = offset_of(kids[s])) < 0) {
                index = next++;
                stack[sp++] = {kids[s], index, it.depth + 1};
                // Its right child lies far ahead in the tree's slots: fetch it
                // now, as its parent will be visited soon (the right one next).
                __builtin_prefetch(&tree[c.link]);
            }
            set_slot(out[it.node], s, c, index);
        }
    }
    st.cost = cost;
    st.leaves = leaves;
    st.max_depth = max_depth;
    return next;
}

// Flattens the binary tree: one BvhNode64 per interior node, leaves inline in
// their parent's slot (Aila & Laine 2009 layout). The nodes above the
// subtrees first, then each subtree's, left to right, each flattened by a
// thread at an offset known from the leaf counts; the sums are taken in a
// fixed order, so the result does not depend on the threads.
void flatten(const bvh_build::Tree& t, Bvh& bvh, float traversal_cost, int threads) {
    const TreeNode* tree = t.nodes.get();
    const float root_area = std::max(node_area(tree[0]), 1e-30f);
    BvhStats& st = bvh.stats;
    if (tree[0].count) {  // the whole tree is one leaf
        BvhNode64 root{};
        set_slot(root, 0, tree[0], 0);
        set_slot(root, 1, tree[0], 0);
        root.child1 = ~0;
        root.count1 = 0;
        bvh.nodes.push_back(root);
        st.leaf_count = 1;
        st.max_depth = 1;
        st.sah_cost = traversal_cost + tree[0].count;
        return;
    }
    // Where each subtree that is not a single leaf starts.
    struct Start {
        std::uint32_t slot;
        int offset;
        std::size_t subtree;
    };
    std::vector<Start> starts;
    std::size_t total = t.top_interior;
    for (std::size_t i = 0; i < t.subtrees.size(); ++i) {
        const bvh_build::Subtree& s = t.subtrees[i];
        if (tree[s.slot].count) continue;  // a leaf: its parent holds it inline
        starts.push_back({s.slot, int(total), i});
        total += s.leaves - 1;
    }
    bvh.nodes.reserve(total);
    bvh_build::advise_huge_pages(bvh.nodes.data(), total * sizeof(BvhNode64));
    bvh.nodes.resize(total);
    BvhNode64* out = bvh.nodes.data();
    std::vector<FlatStats> part(starts.size());
    FlatStats top;
    if (t.top_interior > 0) {
        std::vector<Start> by_slot = starts;
        std::sort(by_slot.begin(), by_slot.end(), [](const Start& a, const Start& b) { return a.slot < b.slot; });
        const int end = flatten_from(tree, 0, 1, 0, out, root_area, traversal_cost, top, [&](std::uint32_t slot) {
            const auto it = std::lower_bound(by_slot.begin(), by_slot.end(), slot,
                                             [](const Start& a, std::uint32_t v) { return a.slot < v; });
            return it != by_slot.end() && it->slot == slot ? it->offset : -1;
        });
        if (std::size_t(end) != t.top_interior) throw std::logic_error("BVH flatten: the top levels' node count differs");
    }
    std::atomic<std::size_t> next{0};
    bvh_build::fork_join(std::min(threads, int(std::max<std::size_t>(starts.size(), 1))), [&](int) {
        for (std::size_t k; (k = next.fetch_add(1)) < starts.size();) {
            const bvh_build::Subtree& s = t.subtrees[starts[k].subtree];
            flatten_from(tree, s.slot, s.depth, starts[k].offset, out, root_area, traversal_cost, part[k],
                         [](std::uint32_t) { return -1; });
        }
    });
    FlatStats all = top;
    for (const FlatStats& p : part) {
        all.cost += p.cost;
        all.leaves += p.leaves;
        all.max_depth = std::max(all.max_depth, p.max_depth);
    }
    st.leaf_count = all.leaves;
    st.max_depth = all.max_depth;
    st.sah_cost = all.cost;
}

}  // namespace

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

    const bvh_build::Tree tree = bvh_build::build_tree(vertices, opt);
    Bvh bvh;
    flatten(tree, bvh, opt.traversal_cost, opt.threads);
    bvh.triangles.reserve(n);
    bvh_build::advise_huge_pages(bvh.triangles.data(), n * sizeof(TriVerts));
    bvh.triangles.resize(n);
    const bvh_build::Ref* refs = tree.refs.get();
    // By chunks handed out one at a time, so a thread that starts late holds nobody up.
    constexpr std::size_t kChunk = 1 << 14;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    std::atomic<std::size_t> next_chunk{0};
    bvh_build::fork_join(int(std::min<std::size_t>(std::size_t(opt.threads), chunks)), [&](int) {
        for (std::size_t k; (k = next_chunk.fetch_add(1)) < chunks;)
            for (std::size_t i = k * kChunk; i < std::min(n, (k + 1) * kChunk); ++i) {
                TriVerts& tv = bvh.triangles[i];
                const std::size_t s = refs[i].prim;
                if (i + 8 < n) __builtin_prefetch(&vertices[3 * std::size_t(refs[i + 8].prim)]);
                for (int a = 0; a < 3; ++a) {
                    tv.v0[a] = vertices[3 * s][a];
                    tv.v1[a] = vertices[3 * s + 1][a];
                    tv.v2[a] = vertices[3 * s + 2][a];
                }
                tv.prim = std::uint32_t(s);
                tv.light = CLP_NO_LIGHT;  // the renderer marks emitters
                tv.pad2 = 0;
            }
    });
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
