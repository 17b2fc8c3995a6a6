// Watertightness (robustness suite, item 1): closed meshes hit by rays aimed
// exactly at their vertices and edges, from inside and outside, through the
// renderer's BVH traversal and watertight triangle test. Expected result: no
// ray passes through, zero leaks (an exact count, no tolerance: the watertight
// test of Woop et al. 2013 guarantees it for rays through shared edges and
// vertices, and the slab test's +-0 handling keeps the boxes closed too).
//
// CI traces about 1.2 million rays; CLPATH_ROBUSTNESS_FULL=1 traces the
// 10^7 rays the robustness suite aims at, and more (4 million per mesh, 12 million in all).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include <glm/gtc/constants.hpp>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"
#include "robustness/robustness_probes.hpp"
#include "scene/shapes.hpp"

using namespace clpath;

namespace {

bool full_run() {
    const char* v = std::getenv("CLPATH_ROBUSTNESS_FULL");
    return v && *v && std::string(v) != "0";
}

// The unit cube, each face split into n x n cells of two triangles; the grid
// points are dyadic, so shared vertices are bit-identical and axis-aligned
// targets (face centres, grid lines through 0) give exact +-0 ray components.
std::vector<glm::vec3> split_cube(int n) {
    std::vector<glm::vec3> out;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-0.5f, 0.5f}) {
            auto p = [&](int i, int j) {
                glm::vec3 v;
                v[axis] = side;
                v[(axis + 1) % 3] = float(i) / float(n) - 0.5f;
                v[(axis + 2) % 3] = float(j) / float(n) - 0.5f;
                return v;
            };
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    glm::vec3 a = p(i, j), b = p(i + 1, j), c = p(i + 1, j + 1), d = p(i, j + 1);
                    // Alternate diagonals, so vertices have 4 and 8 triangles around them.
                    if ((i + j) % 2) out.insert(out.end(), {a, b, c, a, c, d});
                    else out.insert(out.end(), {a, b, d, b, c, d});
                }
        }
    return out;
}

// A cone of `segments` slivers around its apex, closed by a fan of as many
// slivers around the centre of its base: two vertices shared by thousands of
// needle-thin triangles.
std::vector<glm::vec3> sliver_cone(int segments) {
    std::vector<glm::vec3> out;
    const glm::vec3 apex(0, 1, 0), centre(0, 0, 0);
    auto ring = [&](int k) {
        const float a = 2 * glm::pi<float>() * float(k % segments) / float(segments);
        return glm::vec3(std::cos(a), 0, std::sin(a));
    };
    for (int k = 0; k < segments; ++k) {
        out.insert(out.end(), {apex, ring(k + 1), ring(k)});
        out.insert(out.end(), {centre, ring(k), ring(k + 1)});
    }
    return out;
}

// Every vertex, every edge midpoint and one random point on every edge.
std::vector<float> targets_of(const std::vector<glm::vec3>& mesh, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> t;
    auto add = [&](glm::vec3 p) { t.insert(t.end(), {p.x, p.y, p.z}); };
    for (std::size_t i = 0; i < mesh.size(); i += 3)
        for (int e = 0; e < 3; ++e) {
            const glm::vec3 a = mesh[i + e], b = mesh[i + (e + 1) % 3];
            add(a);
            add(0.5f * (a + b));
            add(a + u(rng) * (b - a));
        }
    return t;
}

struct Leaks {
    std::uint64_t rays = 0, leaks = 0, first = 0;
};

Leaks shoot(const std::vector<glm::vec3>& mesh, glm::vec3 centre, float radius, std::uint64_t rays) {
    const Bvh bvh = build_bvh(mesh);
    check_bvh(bvh, mesh.size() / 3);
    const auto targets = targets_of(mesh, 7);
    const std::uint32_t tcount = std::uint32_t(targets.size() / 3);
    Kernel k = test::device().kernel(test::robustness_program(), "probe_watertight");
    Buffer nodes = test::upload(device_nodes(Accel::Bvh, bvh, test::node_layout())), tris = test::upload(bvh.triangles), tb = test::upload(targets);
    Buffer leaks = test::upload(std::vector<std::uint32_t>{0});
    Buffer first = test::upload(std::vector<std::uint64_t>{0});
    const float margin = 0.05f;  // far below any chord through these meshes' insides
    const std::uint32_t batch = 1u << 20;
    for (std::uint64_t done = 0; done < rays; done += batch) {
        const std::uint32_t n = std::uint32_t(std::min<std::uint64_t>(batch, rays - done));
        k.arg(0, nodes).arg(1, tris).arg(2, tb).arg(3, tcount).arg(4, centre.x).arg(5, centre.y).arg(6, centre.z);
        k.arg(7, radius).arg(8, margin).arg(9, cl_ulong(done)).arg(10, n).arg(11, 1u).arg(12, leaks).arg(13, first);
        test::run(k, n);
    }
    return {rays, test::download<std::uint32_t>(leaks, 1)[0], test::download<std::uint64_t>(first, 1)[0]};
}

std::uint64_t rays_per_mesh() { return full_run() ? 4'000'000ull : 400'000ull; }

void expect_watertight(const char* what, const std::vector<glm::vec3>& mesh, glm::vec3 centre, float radius) {
    const Leaks l = shoot(mesh, centre, radius, rays_per_mesh());
    EXPECT_EQ(l.leaks, 0u) << what << ": " << l.leaks << " of " << l.rays << " rays passed through (first: ray "
                           << l.first << ")";
    std::fprintf(stderr, "[ rays    ] %s: %llu rays, %llu leaks\n", what, (unsigned long long)l.rays,
                 (unsigned long long)l.leaks);
}

}  // namespace

TEST(Watertight, FinelySplitCube) { expect_watertight("split cube 32x32", split_cube(32), {0, 0, 0}, 0.3f); }

TEST(Watertight, Icosphere) { expect_watertight("icosphere 4", make_icosphere(4), {0, 0, 0}, 0.5f); }

TEST(Watertight, FanOfSlivers) {
    // The inscribed sphere of this cone has radius 1 / (1 + sqrt 2) ~ 0.414 about y = 0.414.
    // Every ray near the apex visits every sliver's box: 1024 in CI, 4096 in the full run.
    const int n = full_run() ? 4096 : 1024;
    expect_watertight(("sliver cone " + std::to_string(n)).c_str(), sliver_cone(n), {0, 0.414f, 0}, 0.2f);
}

// The count itself must be able to see a hole: a cube with one triangle
// removed leaks for the rays aimed into that hole.
TEST(Watertight, CountSeesAHole) {
    auto mesh = split_cube(8);
    mesh.erase(mesh.begin(), mesh.begin() + 3);
    const Leaks l = shoot(mesh, {0, 0, 0}, 0.3f, 200'000);
    EXPECT_GT(l.leaks, 0u);
}
