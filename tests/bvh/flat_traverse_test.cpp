// The flat structure (bvh/flat.hpp: one box per object, the thesis
// renderer's) holds every triangle once inside its object's box, and its
// device traversal (kernels/traverse_flat.cl, -DCLP_ACCEL_FLAT, through the
// ray-batch kernels) finds what brute force finds and what the BVH finds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bench/cpu_traversal.hpp"
#include "bench/ray_batches.hpp"
#include "bvh/accel.hpp"
#include "bvh/flat.hpp"
#include "cl/embedded_sources.hpp"
#include "render/kernel_programs.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/shapes.hpp"
#include "support/hit_agreement.hpp"
#include "support/random_geometry.hpp"
#include "support/test_device.hpp"
#include "support/traversal_probes.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

// Several objects: random soups and an icosphere, each its own object id.
struct Objects {
    std::vector<glm::vec3> verts;
    std::vector<std::uint32_t> object;
};

Objects some_objects(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1, 1), size(0.02f, 0.3f);
    Objects o;
    for (std::uint32_t obj = 0; obj < 5; ++obj) {
        const glm::vec3 centre(pos(rng), pos(rng), pos(rng));
        for (int t = 0; t < 200; ++t) {
            const glm::vec3 c = centre + 0.4f * glm::vec3(pos(rng), pos(rng), pos(rng));
            const float s = size(rng);
            for (int k = 0; k < 3; ++k) o.verts.push_back(c + s * glm::vec3(pos(rng), pos(rng), pos(rng)));
            o.object.push_back(obj);
        }
    }
    for (const auto& v : transformed(make_icosphere(3), shape_transform({0.2f, -0.3f, 0.1f}, {0, 0, 0}, glm::vec3(0.5f))))
        o.verts.push_back(v);
    o.object.resize(o.verts.size() / 3, 5);
    return o;
}

// The shared random rays as batch rays; every third one bounded, as shadow rays are.
std::vector<BatchRay> batch_rays(const std::vector<test::TestRay>& rays) {
    std::vector<BatchRay> out(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        store3(out[i].o, rays[i].o);
        store3(out[i].d, rays[i].d);
        out[i].tmax = i % 3 == 0 ? 1.0f : INFINITY;
        out[i].src = std::uint32_t(i);
    }
    return out;
}

struct DeviceHits {
    std::vector<Hit> closest;
    std::vector<int> any;
};

DeviceHits trace(const Bvh& structure, Accel accel, const std::vector<BatchRay>& rays) {
    Context& ctx = test::device();
    const ProgramSpec spec = ray_batch_program(accel, kernel_code(ctx.device()));
    BuildResult built = build_program(ctx, program_source(spec.roots), spec.options);
    Kernel closest = ctx.kernel(built.program.get(), "batch_trace_closest");
    Kernel any = ctx.kernel(built.program.get(), "batch_trace_any");
    const std::uint32_t n = std::uint32_t(rays.size());
    Buffer nodes = test::upload(device_nodes(accel, structure, node_layout(kernel_code(ctx.device()), false))), tris = test::upload(structure.triangles), rb = test::upload(rays);
    Buffer hits = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "hits");
    Buffer occ = ctx.buffer(n * sizeof(int), CL_MEM_READ_WRITE, "occluders");
    closest.arg(0, nodes).arg(1, tris).arg(2, rb).arg(3, hits).arg(4, n);
    any.arg(0, nodes).arg(1, tris).arg(2, rb).arg(3, occ).arg(4, n);
    test::run(closest, n);
    test::run(any, n);
    return {test::download<Hit>(hits, n), test::download<int>(occ, n)};
}

// Brute force through the CPU reference: one leaf holding every triangle.
Bvh one_leaf(const std::vector<glm::vec3>& verts) {
    Bvh b = build_flat(verts, std::vector<std::uint32_t>(verts.size() / 3, 0));
    b.nodes.resize(1);
    b.nodes[0].child1 = ~0;
    b.nodes[0].count1 = 0;
    return b;
}

std::int64_t prim_of(const Bvh& s, int tri) { return tri < 0 ? -1 : std::int64_t(s.triangles[std::size_t(tri)].prim); }

}  // namespace

TEST(FlatStructure, HoldsEveryTriangleInItsObjectsBox) {
    const Objects o = some_objects(1);
    const Bvh flat = build_flat(o.verts, o.object);
    EXPECT_NO_THROW(check_flat(flat, o.object.size()));
    EXPECT_EQ(flat.stats.leaf_count, 6u);
    EXPECT_EQ(flat.stats.node_count, 4u);  // three records of two objects, then the terminator
    // Every triangle sits with its own object's run.
    for (std::size_t i = 1; i < flat.triangles.size(); ++i)
        EXPECT_LE(o.object[flat.triangles[i - 1].prim], o.object[flat.triangles[i].prim]);
}

TEST(FlatStructure, OddAndEvenObjectCountsAreTerminated) {
    for (std::uint32_t objects : {1u, 2u, 3u}) {
        std::vector<glm::vec3> v;
        std::vector<std::uint32_t> id;
        for (std::uint32_t k = 0; k < objects; ++k) {
            for (const auto& p : transformed(make_box(), shape_transform({float(k), 0, 0}, {0, 0, 0}, glm::vec3(0.5f))))
                v.push_back(p);
            id.resize(v.size() / 3, k);
        }
        const Bvh flat = build_flat(v, id);
        EXPECT_NO_THROW(check_flat(flat, id.size())) << objects << " objects";
        EXPECT_EQ(flat.nodes.size(), objects / 2 + 1);
    }
}

TEST(FlatStructure, RejectsMismatchedObjectIds) {
    try {
        build_flat(make_box(), {0, 0});
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2 object ids for 12 triangles"), std::string::npos) << e.what();
    }
}

TEST(FlatTraversal, EqualsBruteForceAndTheBvh) {
    const Objects o = some_objects(2);
    const auto test_rays = test::random_rays(20000, 3, o.verts);
    const auto rays = batch_rays(test_rays);
    const auto tris = test::device_triangles(o.verts);
    const Bvh flat = build_flat(o.verts, o.object);
    const Bvh bvh = build_bvh(o.verts);
    const Bvh brute = one_leaf(o.verts);
    const DeviceHits f = trace(flat, Accel::Flat, rays);
    const DeviceHits b = trace(bvh, Accel::Bvh, rays);
    std::size_t hits = 0, ties = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        // Flat and BVH run the same float triangle test: the same closest
        // distance exactly, and the same triangle but at an exact tie.
        ASSERT_EQ(f.closest[i].t, b.closest[i].t) << "ray " << i;
        const std::int64_t fp = prim_of(flat, f.closest[i].tri), bp = prim_of(bvh, b.closest[i].tri);
        ASSERT_TRUE(test::same_hit_or_exact_tie(tris, test_rays[i], int(fp), int(bp), f.closest[i].t))
            << "ray " << i << ": flat hit triangle " << fp << ", the BVH " << bp;
        ASSERT_EQ(f.any[i] >= 0, b.any[i] >= 0) << "ray " << i;
        const CpuHit c = cpu_closest_hit(brute, rays[i]);
        ASSERT_EQ(fp >= 0, c.prim >= 0) << "ray " << i;
        ASSERT_EQ(f.any[i] >= 0, cpu_any_hit(brute, rays[i]) >= 0) << "ray " << i;
        if (fp < 0) continue;
        ++hits;
        // The float distance is within the Woop test's rounding of the exact one (kTieTolerance bounds it).
        const double scale = c.t + std::max({std::abs(rays[i].o[0]), std::abs(rays[i].o[1]), std::abs(rays[i].o[2])});
        ASSERT_LE(std::abs(double(f.closest[i].t) - c.t), kTieTolerance * scale) << "ray " << i;
        if (fp != c.prim) {
            // Another triangle than the double-precision walk's (a shared
            // edge): the float test must still hit the one reported alone at
            // the reported distance, or it was mislabelled.
            ++ties;
            ASSERT_EQ(test::trace_brute({tris[std::size_t(fp)]}, test::packed({test_rays[i]})).t[0], f.closest[i].t)
                << "ray " << i;
        }
    }
    EXPECT_GT(hits, rays.size() / 4) << "the test should see hits";
    EXPECT_LT(ties, rays.size() / 1000) << "ties are rays through shared edges, rare";
}

TEST(FlatTraversal, ScalingSceneObjectsAreTheRoomPartsAndTheSphere) {
    const Scene s = scaling_scene(1000);
    ASSERT_EQ(s.triangle_object.size(), s.triangle_count());
    const Bvh flat = build_accel(Accel::Flat, s.vertices, s.triangle_object);
    check_flat(flat, s.triangle_count());
    EXPECT_EQ(flat.stats.leaf_count, 7u);  // five walls, the lamp, the sphere
}
