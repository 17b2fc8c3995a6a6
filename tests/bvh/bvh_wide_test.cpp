// The 4-wide BVH the kernels traverse (host/bvh/wide.hpp): its invariants on
// ordinary, degenerate and deep trees, the depth bound the traversal stack
// relies on, and controls showing that the check rejects broken trees.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "bvh/wide.hpp"
#include "scene/shapes.hpp"

using namespace clpath;

namespace {

std::vector<glm::vec3> soup(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<glm::vec3> v;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) v.push_back(c + 0.1f * glm::vec3(u(rng), u(rng), u(rng)));
    }
    return v;
}

// Both rules' trees pass check_wide; returns the default rule's depth.
int checked_depth(const Bvh& bvh) {
    const std::vector<Bvh4Node128> wide = widen_bvh(bvh.nodes);
    int depth = 0;
    EXPECT_NO_THROW(depth = check_wide(wide, bvh));
    EXPECT_LE(wide.size(), bvh.nodes.size()) << "collapsing never adds nodes";
    EXPECT_LE(depth, bvh.stats.max_depth) << "each wide level spans at least one binary level";
    const std::vector<Bvh4Node128> two = widen_bvh(bvh.nodes, WideningRule::TwoLevels);
    int two_depth = 0;
    EXPECT_NO_THROW(two_depth = check_wide(two, bvh));
    EXPECT_LE(two.size(), bvh.nodes.size());
    // Each wide level spans two binary ones (root = 1 on both sides).
    EXPECT_LE(two_depth, (bvh.stats.max_depth + 1) / 2);
    // Eight children: the same invariants, and no deeper than four.
    const std::vector<Bvh8Node256> eight = widen_bvh8(bvh.nodes);
    int eight_depth = 0;
    EXPECT_NO_THROW(eight_depth = check_wide(eight, bvh));
    EXPECT_LE(eight.size(), wide.size()) << "eight children need no more nodes than four";
    EXPECT_LE(eight_depth, depth);
    const std::vector<Bvh8Node256> eight_two = widen_bvh8(bvh.nodes, WideningRule::TwoLevels);
    int eight_two_depth = 0;
    EXPECT_NO_THROW(eight_two_depth = check_wide(eight_two, bvh));
    EXPECT_LE(eight_two_depth, (bvh.stats.max_depth + 1) / 2);
    return depth;
}

// Slot `slot` of n: the flat box [lo, hi] in z = 0, and its child and count.
void set_slot(BvhNode64& n, int slot, glm::vec2 lo, glm::vec2 hi, int child, std::uint32_t count) {
    float* l = slot ? n.lo1 : n.lo0;
    float* h = slot ? n.hi1 : n.hi0;
    l[0] = lo.x, l[1] = lo.y, l[2] = 0;
    h[0] = hi.x, h[1] = hi.y, h[2] = 0;
    (slot ? n.child1 : n.child0) = child;
    (slot ? n.count1 : n.count0) = count;
}

// A binary tree of the given depth that widens as deep as the bound allows:
// chain node i holds a twig (a node of two one-triangle leaves) and chain
// node i + 1; the last chain node holds two twigs. Every wide node then spans
// exactly two binary levels. All boxes are one box around everything, which
// contains whatever is below it.
Bvh twig_chain(int depth) {
    Bvh b;
    const int chain = depth - 1;  // twigs hang one level below the chain
    auto set = [](BvhNode64& n, int slot, int child, std::uint32_t count, float size) {
        float* lo = slot ? n.lo1 : n.lo0;
        float* hi = slot ? n.hi1 : n.hi0;
        for (int a = 0; a < 3; ++a) lo[a] = 0, hi[a] = a == 2 ? 0 : size;
        (slot ? n.child1 : n.child0) = child;
        (slot ? n.count1 : n.count0) = count;
    };
    const float size = float(2 * chain + 4);
    b.nodes.resize(std::size_t(chain), BvhNode64{});
    auto add_twig = [&]() {
        const int index = int(b.nodes.size());
        b.nodes.emplace_back(BvhNode64{});
        for (int s = 0; s < 2; ++s) {
            const int tri = int(b.triangles.size());
            TriVerts t{};
            const float x = float(tri) * 0.5f;
            const float v[3][3] = {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}};
            for (int a = 0; a < 3; ++a) t.v0[a] = v[0][a], t.v1[a] = v[1][a], t.v2[a] = v[2][a];
            t.prim = std::uint32_t(tri);
            b.triangles.push_back(t);
            set(b.nodes[std::size_t(index)], s, ~tri, 1, size);
        }
        return index;
    };
    for (int i = 0; i < chain; ++i) {
        const int twig = add_twig();
        set(b.nodes[std::size_t(i)], 0, twig, 0, size);
        const int next = i + 1 < chain ? i + 1 : add_twig();
        set(b.nodes[std::size_t(i)], 1, next, 0, size);
    }
    b.stats.max_depth = depth;
    return b;
}

}  // namespace

TEST(BvhWide, InvariantsOnOrdinaryMeshes) {
    EXPECT_GE(checked_depth(build_bvh(soup(20000, 1))), 3);
    checked_depth(build_bvh(make_icosphere(4)));
    checked_depth(build_bvh(make_box()));
}

TEST(BvhWide, OneAndTwoTriangles) {
    const Bvh one = build_bvh(soup(1, 2));
    const std::vector<Bvh4Node128> wide = widen_bvh(one.nodes);
    ASSERT_EQ(wide.size(), 1u);
    EXPECT_EQ(wide[0].count[0], 1u);
    EXPECT_EQ(wide[0].child[1], 0) << "the other slots are empty";
    EXPECT_EQ(check_wide(wide, one), 1);
    checked_depth(build_bvh(soup(2, 3)));
}

TEST(BvhWide, IdenticalTriangles) {
    std::vector<glm::vec3> v;
    for (int i = 0; i < 5000; ++i) v.insert(v.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    checked_depth(build_bvh(v));
}

TEST(BvhWide, DeepestBinaryTreeFitsTheStack) {
    const Bvh chain = twig_chain(CLP_BVH_MAX_DEPTH);
    const std::vector<Bvh4Node128> two = widen_bvh(chain.nodes, WideningRule::TwoLevels);
    EXPECT_EQ(check_wide(two, chain), CLP_BVH4_MAX_DEPTH);
    // All boxes are equal, so opening the largest child first goes down one
    // chain link per wide level: too deep, and the default rule falls back.
    const std::vector<Bvh4Node128> wide = widen_bvh(chain.nodes);
    EXPECT_EQ(check_wide(wide, chain), CLP_BVH4_MAX_DEPTH);
    ASSERT_EQ(wide.size(), two.size());
    EXPECT_EQ(std::memcmp(wide.data(), two.data(), wide.size() * sizeof(Bvh4Node128)), 0);
    // Eight children fall back the same way and stay within CLP_BVH8_MAX_DEPTH.
    EXPECT_LE(check_wide(widen_bvh8(chain.nodes), chain), CLP_BVH8_MAX_DEPTH);
}

// root = [A, B]; A = [A1, leaf 0] with A1 = [leaf 3, leaf 4] nearly as large
// as A; B = [leaf 1, leaf 2], small. Opening the largest child first opens A,
// then A1, and keeps B as the root's interior child; the two-level rule opens
// A and B and keeps A1.
TEST(BvhWide, LargestFirstOpensTheLargestChildren) {
    Bvh b;
    b.nodes.resize(4, BvhNode64{});
    set_slot(b.nodes[0], 0, {0, 0}, {10, 10}, 1, 0);  // A
    set_slot(b.nodes[0], 1, {20, 0}, {21, 1}, 2, 0);  // B
    set_slot(b.nodes[1], 0, {0, 0}, {9, 9}, 3, 0);    // A1
    set_slot(b.nodes[1], 1, {9.5f, 9.5f}, {10, 10}, ~0, 1);
    set_slot(b.nodes[2], 0, {20, 0}, {20.5f, 0.5f}, ~1, 1);
    set_slot(b.nodes[2], 1, {20.5f, 0.5f}, {21, 1}, ~2, 1);
    set_slot(b.nodes[3], 0, {0, 0}, {1, 1}, ~3, 1);
    set_slot(b.nodes[3], 1, {8, 8}, {9, 9}, ~4, 1);
    // Leaf i's triangle spans its leaf's box: corner, corner + (s, 0), corner + (s, s).
    const glm::vec2 corner[5] = {{9.5f, 9.5f}, {20, 0}, {20.5f, 0.5f}, {0, 0}, {8, 8}};
    const float size[5] = {0.5f, 0.5f, 0.5f, 1, 1};
    for (int i = 0; i < 5; ++i) {
        TriVerts t{};
        t.v0[0] = corner[i].x, t.v0[1] = corner[i].y;
        t.v1[0] = corner[i].x + size[i], t.v1[1] = corner[i].y;
        t.v2[0] = corner[i].x + size[i], t.v2[1] = corner[i].y + size[i];
        t.prim = std::uint32_t(i);
        b.triangles.push_back(t);
    }
    b.stats.max_depth = 3;
    // lo_x + hi_x of the root's one interior child.
    auto interior_x = [](const Bvh4Node128& root) {
        int interior = -1;
        for (int k = 0; k < 4; ++k)
            if (root.child[k] > 0) {
                EXPECT_EQ(interior, -1) << "one interior child";
                interior = k;
            }
        return interior < 0 ? -1.0f : root.lo_x[interior] + root.hi_x[interior];
    };
    const std::vector<Bvh4Node128> largest = widen_bvh(b.nodes);
    ASSERT_NO_THROW(check_wide(largest, b));
    EXPECT_EQ(interior_x(largest[0]), 41.0f) << "B (x in [20, 21]) kept, A1 opened";
    const std::vector<Bvh4Node128> two = widen_bvh(b.nodes, WideningRule::TwoLevels);
    ASSERT_NO_THROW(check_wide(two, b));
    EXPECT_EQ(interior_x(two[0]), 9.0f) << "control: A1 (x in [0, 9]) kept, B opened";
}

TEST(BvhWide, ControlBrokenTreesAreRejected) {
    const Bvh bvh = build_bvh(soup(2000, 4));
    const std::vector<Bvh4Node128> good = widen_bvh(bvh.nodes);
    ASSERT_NO_THROW(check_wide(good, bvh));
    std::vector<Bvh4Node128> w = good;
    w[1].hi_x[0] = w[1].lo_x[0];  // a leaf or child box shrunk to a plane
    EXPECT_THROW(check_wide(w, bvh), std::logic_error);
    w = good;
    w[0].child[1] = w[0].child[0];  // a node reached twice, another never
    EXPECT_THROW(check_wide(w, bvh), std::logic_error);
    // A tree one binary level too deep widens one wide level too deep.
    const Bvh chain = twig_chain(CLP_BVH_MAX_DEPTH + 2);
    EXPECT_THROW(check_wide(widen_bvh(chain.nodes), chain), std::logic_error);
    EXPECT_THROW(widen_bvh({}), std::invalid_argument);
    // The same controls for eight children.
    const std::vector<Bvh8Node256> good8 = widen_bvh8(bvh.nodes);
    ASSERT_NO_THROW(check_wide(good8, bvh));
    std::vector<Bvh8Node256> w8 = good8;
    w8[1].hi_x[0] = w8[1].lo_x[0];
    EXPECT_THROW(check_wide(w8, bvh), std::logic_error);
    w8 = good8;
    w8[0].child[1] = w8[0].child[0];
    EXPECT_THROW(check_wide(w8, bvh), std::logic_error);
    EXPECT_THROW(widen_bvh8({}), std::invalid_argument);
}
