// BVH traversal on the device (kernels/traverse_bvh4.cl) equals brute force over
// every triangle (same distance, same triangle), for closest and any hit,
// on several meshes; and closed meshes let no ray through.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "bvh/bvh.hpp"
#include "scene/shapes.hpp"
#include "support/hit_agreement.hpp"
#include "support/random_geometry.hpp"
#include "support/test_device.hpp"
#include "support/traversal_probes.hpp"

using namespace clpath;

namespace {

using test::trace_bvh;

void expect_bvh_equals_brute(const std::vector<glm::vec3>& verts, std::uint32_t seed) {
    const std::size_t n = 20000;
    const auto rays = test::random_rays(n, seed, verts);
    const Bvh bvh = build_bvh(verts);
    check_bvh(bvh, verts.size() / 3);
    const auto tris = test::device_triangles(verts);
    const auto a = trace_bvh(bvh, test::packed(rays), std::vector<float>(n, INFINITY));
    const auto b = test::trace_brute(tris, test::packed(rays));
    std::size_t hits = 0, ties = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(a.t[i], b.t[i]) << "ray " << i;
        // Another triangle than brute force's only at exactly the same distance (a shared edge).
        ASSERT_TRUE(test::same_hit_or_exact_tie(tris, rays[i], a.prim[i], b.prim[i], b.t[i]))
            << "ray " << i << ": the BVH hit triangle " << a.prim[i] << ", brute force " << b.prim[i] << ", at t "
            << b.t[i];
        ties += a.prim[i] != b.prim[i];
        ASSERT_EQ(a.any[i], b.prim[i] >= 0) << "ray " << i;
        hits += b.prim[i] >= 0;
    }
    EXPECT_GT(hits, n / 4) << "the test should see hits";
    EXPECT_LT(ties, n / 1000) << "ties are rays through shared edges, rare";
}

}  // namespace

TEST(BvhTraversal, RandomSoupEqualsBruteForce) { expect_bvh_equals_brute(test::random_soup(3000, 1, 0.01f, 0.2f), 2); }

TEST(BvhTraversal, IcosphereEqualsBruteForce) { expect_bvh_equals_brute(make_icosphere(4), 3); }

TEST(BvhTraversal, FewTrianglesEqualsBruteForce) {
    expect_bvh_equals_brute(test::random_soup(1, 4, 0.01f, 0.2f), 5);
    expect_bvh_equals_brute(test::random_soup(3, 6, 0.01f, 0.2f), 7);
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
