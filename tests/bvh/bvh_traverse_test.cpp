// BVH traversal on the device (kernels/traverse.cl) equals brute force over
// every triangle (same distance, same triangle), for closest and any hit,
// on several meshes; and closed meshes let no ray through.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/constants.hpp>

#include "bvh/bvh.hpp"
#include "scene/shapes.hpp"
#include "support/test_device.hpp"
#include "support/traversal_probes.hpp"

using namespace clpath;

namespace {

using test::Traced;
using test::trace_bvh;

Traced trace_brute(const std::vector<glm::vec3>& verts, const std::vector<float>& rays) {
    return test::trace_brute(test::device_triangles(verts), rays);
}

std::vector<glm::vec3> random_soup(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1, 1), size(0.01f, 0.2f);
    std::vector<glm::vec3> v;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        const float s = size(rng);
        for (int k = 0; k < 3; ++k) v.push_back(c + s * glm::vec3(pos(rng), pos(rng), pos(rng)));
    }
    return v;
}

// Half the rays aim at a random point of a random triangle, so every mesh,
// however small, sees hits; the other half go anywhere.
std::vector<float> random_rays(std::size_t n, std::uint32_t seed, const std::vector<glm::vec3>& mesh) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.5f, 1.5f), dir(-1, 1), unit(0, 1);
    std::uniform_int_distribution<std::size_t> pick(0, mesh.size() / 3 - 1);
    std::vector<float> r;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 o(pos(rng), pos(rng), pos(rng));
        glm::vec3 d(dir(rng), dir(rng), dir(rng));
        if (i % 2) {
            const std::size_t t = pick(rng);
            float a = unit(rng), b = unit(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            d = mesh[3 * t] + a * (mesh[3 * t + 1] - mesh[3 * t]) + b * (mesh[3 * t + 2] - mesh[3 * t]) - o;
        }
        // Some axis-aligned directions, with signed zeros, where slab tests are fragile.
        if (i % 7 == 0) d = glm::vec3(i % 2 ? -0.0f : 0.0f, 0.0f, dir(rng) < 0 ? -1.0f : 1.0f);
        d = glm::normalize(d);
        for (int k = 0; k < 3; ++k) r.push_back(o[k]);
        for (int k = 0; k < 3; ++k) r.push_back(d[k]);
    }
    return r;
}

void expect_bvh_equals_brute(const std::vector<glm::vec3>& verts, std::uint32_t seed) {
    const std::size_t n = 20000;
    const auto rays = random_rays(n, seed, verts);
    const Bvh bvh = build_bvh(verts);
    check_bvh(bvh, verts.size() / 3);
    const auto a = trace_bvh(bvh, rays, std::vector<float>(n, INFINITY));
    const auto b = trace_brute(verts, rays);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(a.t[i], b.t[i]) << "ray " << i;
        // Two triangles at exactly the same distance (a shared edge) may be found in either order.
        if (a.prim[i] != b.prim[i]) {
            ASSERT_EQ(a.t[i], b.t[i]) << "ray " << i;
        }
        ASSERT_EQ(a.any[i], b.prim[i] >= 0) << "ray " << i;
        hits += b.prim[i] >= 0;
    }
    EXPECT_GT(hits, n / 4) << "the test should see hits";
}

}  // namespace

TEST(BvhTraversal, RandomSoupEqualsBruteForce) { expect_bvh_equals_brute(random_soup(3000, 1), 2); }

TEST(BvhTraversal, IcosphereEqualsBruteForce) { expect_bvh_equals_brute(make_icosphere(4), 3); }

TEST(BvhTraversal, FewTrianglesEqualsBruteForce) {
    expect_bvh_equals_brute(random_soup(1, 4), 5);
    expect_bvh_equals_brute(random_soup(3, 6), 7);
}

TEST(BvhTraversal, AnyHitRespectsTmax) {
    // A wall at z = 1 and rays from the origin along +z: any-hit within
    // tmax < 1 finds nothing, beyond 1 finds the wall.
    auto wall = transformed(make_plane(), shape_transform({0, 0, 1}, {glm::half_pi<float>(), 0, 0}, {4, 1, 4}));
    const Bvh bvh = build_bvh(wall);
    std::vector<float> rays = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1};
    const auto r = trace_bvh(bvh, rays, {0.99f, 1.01f});
    EXPECT_EQ(r.any[0], 0);
    EXPECT_EQ(r.prim[0], -1);
    EXPECT_EQ(r.any[1], 1);
    EXPECT_FLOAT_EQ(r.t[1], 1.0f);
}

TEST(BvhTraversal, ClosedMeshLetsNoRayThrough) {
    // From inside a closed mesh every ray must hit it, also rays aimed exactly
    // at vertices and along edges, through the whole traversal path.
    const auto mesh = make_icosphere(4);
    const Bvh bvh = build_bvh(mesh);
    std::vector<float> rays;
    const glm::vec3 origins[] = {{0, 0, 0}, {0.3f, 0.1f, -0.2f}};
    for (glm::vec3 o : origins)
        for (std::size_t t = 0; t < mesh.size(); t += 3)
            for (int e = 0; e < 3; ++e) {
                const glm::vec3 a = mesh[t + e], b = mesh[t + (e + 1) % 3];
                for (glm::vec3 target : {a, 0.5f * (a + b), a + 0.3f * (b - a)}) {
                    const glm::vec3 d = glm::normalize(target - o);
                    for (int k = 0; k < 3; ++k) rays.push_back(o[k]);
                    for (int k = 0; k < 3; ++k) rays.push_back(d[k]);
                }
            }
    const auto r = trace_bvh(bvh, rays, std::vector<float>(rays.size() / 6, INFINITY));
    std::size_t leaks = 0;
    for (int p : r.prim) leaks += p < 0;
    EXPECT_EQ(leaks, 0u) << "of " << r.prim.size() << " rays";
}
