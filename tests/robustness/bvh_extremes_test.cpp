// BVH extremes (robustness suite, item 5): all triangles sharing one
// centroid, a million overlapping triangles, a single triangle, needles, and
// a staircase of sizes that would make the SAH build a tree as deep as it is
// long. Expected: the builder terminates with every invariant (check_bvh:
// boxes contain their triangles exactly, each triangle once, depth <=
// CLP_BVH_MAX_DEPTH, the traversal stack's size); traversal then equals
// brute force on rays through the densest parts, so the stack bound holds
// where it is used hardest.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"
#include "scene/shapes.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

struct Traced {
    std::vector<float> t;
    std::vector<int> prim;
};

Traced trace(const Bvh& bvh, const std::vector<float>& rays, bool brute) {
    const std::uint32_t n = std::uint32_t(rays.size() / 6);
    Buffer tris = test::upload(bvh.triangles), rb = test::upload(rays);
    Buffer ot = test::device().buffer(n * sizeof(float), CL_MEM_READ_WRITE, "t");
    Buffer op = test::device().buffer(n * sizeof(int), CL_MEM_READ_WRITE, "prim");
    if (brute) {
        Kernel k = test::device().kernel(test::probe_program(), "probe_brute");
        k.arg(0, tris).arg(1, std::uint32_t(bvh.triangles.size())).arg(2, rb).arg(3, ot).arg(4, op).arg(5, n);
        test::run(k, n);
    } else {
        Kernel k = test::device().kernel(test::probe_program(), "probe_trace");
        Buffer nodes = test::upload(device_nodes(Accel::Bvh, bvh, test::node_layout())), tb = test::upload(std::vector<float>(n, INFINITY));
        Buffer oa = test::device().buffer(n * sizeof(int), CL_MEM_READ_WRITE, "any");
        k.arg(0, nodes).arg(1, tris).arg(2, rb).arg(3, tb).arg(4, ot).arg(5, op).arg(6, oa).arg(7, n);
        test::run(k, n);
    }
    return {test::download<float>(ot, n), test::download<int>(op, n)};
}

// Builds, checks the invariants, and compares traversal with brute force on `rays`.
Bvh build_and_trace(const std::vector<glm::vec3>& v, const std::vector<float>& rays) {
    const auto t0 = std::chrono::steady_clock::now();
    const Bvh bvh = build_bvh(v);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_NO_THROW(check_bvh(bvh, v.size() / 3));
    EXPECT_LE(bvh.stats.max_depth, CLP_BVH_MAX_DEPTH);
    std::fprintf(stderr, "[ bvh     ] %zu triangles: %s (%.2f s)\n", v.size() / 3, describe(bvh.stats).c_str(), s);
    const Traced a = trace(bvh, rays, false), b = trace(bvh, rays, true);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < a.t.size(); ++i) {
        EXPECT_EQ(a.t[i], b.t[i]) << "ray " << i;
        hits += b.prim[i] >= 0;
    }
    EXPECT_GT(hits, 0u);
    return bvh;
}

std::vector<float> rays_towards(glm::vec3 target, int n, float spread, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> r;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 o(u(rng) * 3, u(rng) * 3, -3), t = target + spread * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = glm::normalize(t - o);
        r.insert(r.end(), {o.x, o.y, o.z, d.x, d.y, d.z});
    }
    return r;
}

}  // namespace

TEST(BvhExtremes, AllTrianglesShareOneCentroid) {
    std::vector<glm::vec3> v;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 50000; ++i) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        v.insert(v.end(), {a, b, -a - b});  // centroid exactly 0 (in exact arithmetic)
    }
    build_and_trace(v, rays_towards({0, 0, 0}, 256, 0.5f, 1));
}

TEST(BvhExtremes, MillionOverlappingTriangles) {
    std::vector<glm::vec3> v;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-0.01f, 0.01f);
    for (int i = 0; i < 1000000; ++i)
        v.insert(v.end(), {glm::vec3(-1, -1, 0) + u(rng), glm::vec3(1, -1, 0) + u(rng), glm::vec3(0, 1, 0) + u(rng)});
    build_and_trace(v, rays_towards({0, 0, 0}, 16, 0.5f, 2));
}

TEST(BvhExtremes, SingleTriangle) {
    build_and_trace({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, rays_towards({0, 0, 0}, 64, 1.0f, 3));
}

TEST(BvhExtremes, NeedleTriangles) {
    std::vector<glm::vec3> v;
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), dir = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        v.insert(v.end(), {a - 5.0f * dir, a + 5.0f * dir, a + glm::vec3(0, 1e-4f, 0)});
    }
    build_and_trace(v, rays_towards({0, 0, 0}, 512, 1.0f, 4));
}

// Triangles of sizes 1.01^k side by side (from 1e-3 to 4e5): the SAH's
// equal-width bins put most of them in the first bin, so the tree is
// unbalanced (depth 22 for 2000 triangles, against 10 balanced); rays along
// the staircase meet every triangle's box, the longest traversal there is,
// with the deepest stack.
TEST(BvhExtremes, StaircaseCannotExceedTheStack) {
    std::vector<glm::vec3> v;
    for (int k = 0; k < 2000; ++k) {
        const float x = std::pow(1.01f, float(k)), s = 0.001f * x;
        v.insert(v.end(), {glm::vec3(x, -s, -s), glm::vec3(x, s, -s), glm::vec3(x, 0, s)});
    }
    std::vector<float> rays;
    for (int i = 0; i < 64; ++i) {
        const float y = 1e-6f * float(i - 32);
        rays.insert(rays.end(), {0.5f, y, 0, 1, 0, 0});
        rays.insert(rays.end(), {1e9f, y, 0, -1, 0, 0});
    }
    const Bvh b = build_and_trace(v, rays);
    EXPECT_GE(b.stats.max_depth, 16) << "the input should have pushed the tree deeper than balanced";
}
