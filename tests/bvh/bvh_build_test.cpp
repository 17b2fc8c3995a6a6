// The BVH builder (host/bvh/): structure invariants on ordinary and
// degenerate meshes, the depth bound, determinism across thread counts.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>
#include <random>

#include "bvh/bvh.hpp"
#include "cl/program.hpp"
#include "scene/shapes.hpp"
#include "support/random_geometry.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

std::vector<glm::vec3> soup(std::size_t n, std::uint32_t seed, float size = 0.1f) {
    return test::random_soup(n, seed, size, size);
}

Bvh checked(const std::vector<glm::vec3>& v, BvhBuildOptions o = {}) {
    Bvh b = build_bvh(v, o);
    EXPECT_NO_THROW(check_bvh(b, v.size() / 3));
    EXPECT_LE(b.stats.max_depth, CLP_BVH_MAX_DEPTH);
    return b;
}

}  // namespace

TEST(BvhBuild, InvariantsOnOrdinaryMeshes) {
    checked(soup(10000, 1));
    checked(make_icosphere(5));
    checked(transformed(make_box(), shape_transform({1, 2, 3}, {0.1f, 0.2f, 0.3f}, {2, 0.5f, 1})));
}

TEST(BvhBuild, OneAndTwoTriangles) {
    const Bvh one = checked(soup(1, 2));
    EXPECT_EQ(one.nodes.size(), 1u);
    EXPECT_EQ(one.nodes[0].count1, 0u) << "the second slot of a leaf root is empty";
    checked(soup(2, 3));
}

TEST(BvhBuild, AllCentroidsEqual) {
    // 100k triangles of random shape and size around one centre: the SAH
    // finds no split; median splits must. On every axis a triangle's
    // coordinates are s, -s and 0, so its vertex mean and its box centre
    // are both exactly the origin, whichever the builder bins by; the
    // vertices (x, y, 0), (-x, 0, z), (0, -y, -z) span a triangle of area
    // 1.5 |(yz, xz, xy)| > 0: not a degenerate case in disguise.
    std::vector<glm::vec3> v;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.1f, 1);
    for (int i = 0; i < 100000; ++i) {
        const glm::vec3 a(u(rng), u(rng), u(rng));
        v.insert(v.end(), {{a.x, a.y, 0}, {-a.x, 0, a.z}, {0, -a.y, -a.z}});
    }
    for (std::size_t t = 0; t < v.size(); t += 3) {
        const glm::vec3 lo = glm::min(v[t], glm::min(v[t + 1], v[t + 2]));
        const glm::vec3 hi = glm::max(v[t], glm::max(v[t + 1], v[t + 2]));
        ASSERT_EQ(lo + hi, glm::vec3(0)) << "triangle " << t / 3 << ": its box is not centred on the origin";
        ASSERT_EQ(v[t] + v[t + 1] + v[t + 2], glm::vec3(0)) << "triangle " << t / 3 << ": its mean is not the origin";
        ASSERT_GT(glm::length(glm::cross(v[t + 1] - v[t], v[t + 2] - v[t])), 0.0f) << "triangle " << t / 3;
    }
    const Bvh b = checked(v);
    EXPECT_LE(b.stats.leaf_count * 4, v.size() / 3 * 2) << "leaves stay small";
}

TEST(BvhBuild, IdenticalAndDegenerateTriangles) {
    std::vector<glm::vec3> same;
    for (int i = 0; i < 200000; ++i) same.insert(same.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    checked(same);
    std::vector<glm::vec3> degenerate;
    for (int i = 0; i < 1000; ++i) {
        const float x = float(i);
        degenerate.insert(degenerate.end(), {{x, 0, 0}, {x, 0, 0}, {x, 0, 0}});            // a point
        degenerate.insert(degenerate.end(), {{x, 0, 0}, {x + 1, 1, 1}, {x + 2, 2, 2}});    // collinear
        degenerate.insert(degenerate.end(), {{x, 0, 0}, {x + 1e6f, 0, 0}, {x, 1e-6f, 0}}); // needle
    }
    checked(degenerate);
}

TEST(BvhBuild, DeterministicAcrossThreadCounts) {
    const auto v = soup(300000, 5, 0.02f);
    // Large enough for the top levels' parallel binning and partitions; 3
    // threads cut the records into uneven chunks.
    BvhBuildOptions one;
    one.threads = 1;
    const Bvh a = checked(v, one);
    for (int threads : {2, 3, 4}) {
        BvhBuildOptions o;
        o.threads = threads;
        const Bvh b = checked(v, o);
        ASSERT_EQ(a.nodes.size(), b.nodes.size()) << threads << " threads";
        EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode64)), 0) << threads;
        EXPECT_EQ(std::memcmp(a.triangles.data(), b.triangles.data(), a.triangles.size() * sizeof(TriVerts)), 0)
            << threads << " threads";
    }
}

// The tree as a sequence, whatever order its nodes have in memory: each
// node's two slots (box, triangle count, and a leaf's first triangle),
// depth first from the root, slot 0's subtree before slot 1's; then the
// triangles in leaf order.
std::uint64_t tree_digest(const Bvh& b) {
    std::string bytes;
    auto put = [&bytes](const void* p, std::size_t n) { bytes.append(static_cast<const char*>(p), n); };
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const BvhNode64& n = b.nodes[std::size_t(stack.back())];
        stack.pop_back();
        for (int s = 0; s < 2; ++s) {
            const int child = s ? n.child1 : n.child0;
            const std::uint32_t count = s ? n.count1 : n.count0;
            put(s ? n.lo1 : n.lo0, 12);
            put(s ? n.hi1 : n.hi0, 12);
            put(&count, 4);
            if (child < 0 || count) put(&child, 4);
        }
        if (n.child1 >= 0 && !n.count1) stack.push_back(n.child1);
        if (n.child0 >= 0 && !n.count0) stack.push_back(n.child0);
    }
    put(b.triangles.data(), b.triangles.size() * sizeof(TriVerts));
    return fnv1a64(bytes);
}

TEST(BvhBuild, TheFastPathsBuildTheSameTree) {
    // The two-record nodes decided without bins, nodes of 3 to 8 records
    // decided by sorting them by bin, four sets of bins instead of two, the
    // output arrays left for the threads to write, the nodes written as they
    // are built: none may change a bit of the tree. The digest is of the
    // tree the builder made before them (af00287, its general path for every
    // node): taken in this layout-free form from 14b88c6, whose node and
    // triangle bytes were af00287's. A coherent mesh large enough for the
    // parallel top levels, and a random soup for nodes of every size. An
    // intended change of the tree updates it.
    std::vector<glm::vec3> v = make_icosphere(6);
    const std::vector<glm::vec3> s = test::random_soup(30000, 7, 0.001f, 0.05f);
    v.insert(v.end(), s.begin(), s.end());
    for (int threads : {1, 2}) {
        BvhBuildOptions o;
        o.threads = threads;
        const Bvh b = checked(v, o);
        EXPECT_EQ(b.nodes.size(), 76161u) << threads << " threads";
        EXPECT_EQ(tree_digest(b), 0xf35e6a47af3f6065ull) << threads << " threads";
    }
}

TEST(BvhBuild, SahBeatsMedianSplits) {
    // With 2 bins the SAH sees only the midpoint split; more bins must find cheaper trees.
    const auto v = soup(50000, 6, 0.05f);
    BvhBuildOptions coarse, fine;
    coarse.bins = 2;
    fine.bins = 32;
    EXPECT_LT(checked(v, fine).stats.sah_cost, checked(v, coarse).stats.sah_cost);
}

// Bad input gets the project's error type, whose message names what is wrong.
void expect_error(const std::vector<glm::vec3>& v, const BvhBuildOptions& o, const std::string& words) {
    try {
        build_bvh(v, o);
        ADD_FAILURE() << "no error; expected one naming '" << words << "'";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

TEST(BvhBuild, EmptyInputIsAnError) { expect_error({}, {}, "no triangles"); }

TEST(BvhBuild, BadInputIsAnError) {
    auto v = soup(100, 7);
    expect_error({v[0], v[1]}, {}, "2 vertices is not a whole number of triangles");
    BvhBuildOptions o;
    o.bins = 1;
    expect_error(v, o, "bins must be in [2, 256], got 1");
    o = {};
    o.max_leaf_size = 65;
    expect_error(v, o, "leaf size must be in [1, 64], got 65");
    o = {};
    o.traversal_cost = -1;
    expect_error(v, o, "traversal cost");
    v[3 * 42 + 1].y = std::numeric_limits<float>::quiet_NaN();
    expect_error(v, {}, "triangle 42 has a non-finite vertex");
    v[3 * 42 + 1].y = 0;
    v[3 * 97 + 2].z = -std::numeric_limits<float>::infinity();
    expect_error(v, {}, "triangle 97 has a non-finite vertex");
    v[3 * 97 + 2].z = 3e38f;  // huge but finite: no error
    EXPECT_NO_THROW(checked(v));
}
