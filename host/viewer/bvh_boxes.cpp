#include "viewer/bvh_boxes.hpp"

#include <algorithm>
#include <utility>

namespace clpath::viewer {
namespace {

struct Child {
    glm::vec3 lo, hi;
    int child;
    unsigned count;
};

Child child(const BvhNode64& n, int i) {
    if (i == 0) return {{n.lo0[0], n.lo0[1], n.lo0[2]}, {n.hi0[0], n.hi0[1], n.hi0[2]}, n.child0, n.count0};
    return {{n.lo1[0], n.lo1[1], n.lo1[2]}, {n.hi1[0], n.hi1[1], n.hi1[2]}, n.child1, n.count1};
}

// Calls f(child, level) for every non-empty child slot down to max_level,
// iteratively (a degenerate BVH can be deep).
template <class F>
void walk(const BvhNodes& nodes, int max_level, F f) {
    if (nodes.empty()) return;
    std::vector<std::pair<int, int>> stack{{0, 1}};  // (node, level of its children)
    while (!stack.empty()) {
        const auto [node, level] = stack.back();
        stack.pop_back();
        if (level > max_level || node < 0 || std::size_t(node) >= nodes.size()) continue;
        for (int i = 0; i < 2; ++i) {
            const Child c = child(nodes[std::size_t(node)], i);
            if (c.child < 0 && c.count == 0) continue;  // empty slot (root leaf)
            f(c, level);
            if (c.child >= 0) stack.push_back({c.child, level + 1});
        }
    }
}

}  // namespace

std::vector<LevelBox> bvh_boxes(const BvhNodes& nodes, int max_level) {
    std::vector<LevelBox> boxes;
    walk(nodes, max_level, [&](const Child& c, int level) { boxes.push_back({c.lo, c.hi, level}); });
    return boxes;
}

int bvh_levels(const BvhNodes& nodes) {
    int deepest = 0;
    walk(nodes, 1 << 30, [&](const Child&, int level) { deepest = std::max(deepest, level); });
    return deepest;
}

std::vector<glm::vec3> box_edges(const LevelBox& b) {
    auto corner = [&](int i) {
        return glm::vec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
    };
    std::vector<glm::vec3> v;
    v.reserve(24);
    // An edge joins two corners that differ in one axis bit.
    for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit)) {
                v.push_back(corner(i));
                v.push_back(corner(i | bit));
            }
    return v;
}

}  // namespace clpath::viewer
