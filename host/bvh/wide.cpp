#include "bvh/wide.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "util/error.hpp"

namespace clpath {
namespace {

// One child slot of a binary node.
struct Slot {
    const float* lo;
    const float* hi;
    int child;
    std::uint32_t count;
    bool interior() const { return child >= 0; }
    bool empty() const { return child < 0 && count == 0; }
    float area() const {
        const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        return x * y + y * z + z * x;
    }
};

Slot slot_of(const BvhNode64& n, int s) {
    return s == 0 ? Slot{n.lo0, n.hi0, n.child0, n.count0} : Slot{n.lo1, n.hi1, n.child1, n.count1};
}

// Replaces slots[k] (interior) by its binary node's children; returns the new count.
int expand(const BvhNodes& binary, Slot* slots, int n, int k) {
    const std::size_t c = std::size_t(slots[k].child);
    if (c >= binary.size()) throw std::invalid_argument("binary BVH: child index out of range");
    slots[k] = slot_of(binary[c], 0);
    slots[n] = slot_of(binary[c], 1);
    return n + 1;
}

// The collapse into nodes of W children under one rule. LargestFirst gives
// up (an empty vector) as soon as a node would lie deeper than max_depth.
template <int W, class Node>
std::vector<Node> widen(const BvhNodes& binary, WideningRule rule, int max_depth) {
    std::vector<Node> wide(1);
    wide.reserve(binary.size() / 2 + 1);
    struct Item {
        int binary, wide, depth;
    };
    std::vector<Item> stack{{0, 0, 1}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        if (rule == WideningRule::LargestFirst && it.depth > max_depth) return {};
        Slot slots[W];
        int n = 0;
        for (int s = 0; s < 2; ++s) {
            const Slot sl = slot_of(binary[std::size_t(it.binary)], s);
            if (!sl.empty()) slots[n++] = sl;
        }
        if (rule == WideningRule::TwoLevels) {
            // Every interior child gives way to its own children first, so
            // each wide level spans two binary levels.
            const int first = n;
            for (int k = 0; k < first; ++k)
                if (slots[k].interior()) n = expand(binary, slots, n, k);
        }
        // Then, while there is room, the interior child most likely to be
        // entered (the largest surface area) is opened: opening a child
        // saves every ray that enters it one node fetch, and rays enter a
        // box in proportion to its area (the SAH's geometric argument).
        while (n < W) {
            int best = -1;
            for (int k = 0; k < n; ++k)
                if (slots[k].interior() && (best < 0 || slots[k].area() > slots[best].area())) best = k;
            if (best < 0) break;
            n = expand(binary, slots, n, best);
        }
        Node out{};
        for (int k = 0; k < n; ++k) {
            const Slot& sl = slots[k];
            out.lo_x[k] = sl.lo[0], out.lo_y[k] = sl.lo[1], out.lo_z[k] = sl.lo[2];
            out.hi_x[k] = sl.hi[0], out.hi_y[k] = sl.hi[1], out.hi_z[k] = sl.hi[2];
            if (sl.interior()) {
                out.child[k] = int(wide.size());
                out.count[k] = 0;
                wide.emplace_back();
                stack.push_back({sl.child, out.child[k], it.depth + 1});
            } else {
                out.child[k] = sl.child;
                out.count[k] = sl.count;
            }
        }
        // Slots n..W-1 stay empty: child 0, count 0, a zero box the kernel never tests.
        wide[std::size_t(it.wide)] = out;
    }
    return wide;
}

}  // namespace

namespace {

template <int W, class Node>
std::vector<Node> widen_checked(const BvhNodes& binary, WideningRule rule, int max_depth, std::size_t max_nodes) {
    if (binary.empty()) throw std::invalid_argument("cannot widen a BVH with no nodes");
    std::vector<Node> wide;
    if (rule == WideningRule::LargestFirst) wide = widen<W, Node>(binary, WideningRule::LargestFirst, max_depth);
    if (wide.empty()) wide = widen<W, Node>(binary, WideningRule::TwoLevels, max_depth);
    if (wide.size() > max_nodes)
        throw Error("the scene's BVH has " + std::to_string(wide.size()) + " " + std::to_string(W) +
                    "-wide nodes; the kernels address at most " + std::to_string(max_nodes));
    return wide;
}

template <int W, class Node>
int check(const std::vector<Node>& wide, const Bvh& bvh, int max_depth) {
    auto fail = [](const std::string& what) { throw std::logic_error("wide BVH invariant broken: " + what); };
    if (wide.empty()) fail("no root");
    std::vector<int> seen_tri(bvh.triangles.size(), 0), seen_node(wide.size(), 0);
    struct Item {
        std::size_t node;
        int depth;
        float lo[3], hi[3];  // the box its parent holds for it (the root: unbounded)
    };
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<Item> stack{{0, 1, {-inf, -inf, -inf}, {inf, inf, inf}}};
    seen_node[0] = 1;
    int depth = 0;
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        depth = std::max(depth, it.depth);
        if (it.depth > max_depth) fail("deeper than the traversal stack allows (" + std::to_string(max_depth) + ")");
        const Node& n = wide[it.node];
        bool ended = false;
        int used = 0;
        for (int k = 0; k < W; ++k) {
            const float lo[3] = {n.lo_x[k], n.lo_y[k], n.lo_z[k]}, hi[3] = {n.hi_x[k], n.hi_y[k], n.hi_z[k]};
            if (n.child[k] == 0 && n.count[k] == 0) {
                ended = true;
                continue;
            }
            if (ended) fail("a full slot after an empty one");
            ++used;
            for (int a = 0; a < 3; ++a)
                if (!(lo[a] >= it.lo[a] && hi[a] <= it.hi[a])) fail("a child box sticks out of its parent's box");
            if (n.child[k] > 0) {
                const std::size_t c = std::size_t(n.child[k]);
                if (c >= wide.size()) fail("child index out of range");
                if (seen_node[c]++) fail("node " + std::to_string(c) + " reached twice");
                Item next{c, it.depth + 1, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
                stack.push_back(next);
                continue;
            }
            if (n.child[k] == 0) fail("the root as a child");
            const std::size_t first = std::size_t(~n.child[k]), count = n.count[k];
            if (count == 0 || first + count > bvh.triangles.size()) fail("leaf range out of range");
            for (std::size_t i = first; i < first + count; ++i) {
                if (seen_tri[i]++) fail("triangle " + std::to_string(i) + " in two leaves");
                const TriVerts& t = bvh.triangles[i];
                for (const float* v : {t.v0, t.v1, t.v2})
                    for (int a = 0; a < 3; ++a)
                        if (!(v[a] >= lo[a] && v[a] <= hi[a]))
                            fail("triangle " + std::to_string(t.prim) + " sticks out of its leaf box");
            }
        }
        if (used == 0) fail("a node with no children");
    }
    for (std::size_t i = 0; i < seen_node.size(); ++i)
        if (!seen_node[i]) fail("node " + std::to_string(i) + " unreachable");
    for (std::size_t i = 0; i < seen_tri.size(); ++i)
        if (!seen_tri[i]) fail("triangle " + std::to_string(i) + " in no leaf");
    return depth;
}

}  // namespace

std::vector<Bvh4Node128> widen_bvh(const BvhNodes& binary, WideningRule rule) {
    return widen_checked<4, Bvh4Node128>(binary, rule, CLP_BVH4_MAX_DEPTH, std::size_t(CLP_BVH4_MAX_NODES));
}

std::vector<Bvh8Node256> widen_bvh8(const BvhNodes& binary, WideningRule rule) {
    return widen_checked<8, Bvh8Node256>(binary, rule, CLP_BVH8_MAX_DEPTH, std::size_t(CLP_BVH8_MAX_NODES));
}

int check_wide(const std::vector<Bvh4Node128>& wide, const Bvh& bvh) {
    return check<4>(wide, bvh, CLP_BVH4_MAX_DEPTH);
}

int check_wide(const std::vector<Bvh8Node256>& wide, const Bvh& bvh) {
    return check<8>(wide, bvh, CLP_BVH8_MAX_DEPTH);
}

}  // namespace clpath
