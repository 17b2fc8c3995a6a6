// What bench rays hands out for a harness (on_structure: the batch program's
// source and options, the node and triangle buffers; host/bench/ray_files.hpp)
// must be all a harness needs to run clpath's own kernels in its process:
// rebuilt from those alone, the kernels give back the very answers clpath
// saved for the same rays. And a variant of the kernels (RayBenchOptions::ab) is timed
// launch by launch against the built-in ones, its answers compared bitwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "bench/ray_batches.hpp"
#include "cl/embedded_sources.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

struct Saved {
    std::string source, options;
    std::vector<unsigned char> nodes;
    BvhTriangles triangles;
    std::vector<BatchRay> rays[3];
    std::vector<float> results[3];
};

Saved run_and_save() {
    const Scene scene = load_scene("cornell");
    RayBenchOptions o;
    o.width = 32, o.height = 24, o.launches = 1, o.embree = false;
    Saved s;
    o.on_structure = [&](const std::string& source, const std::string& options,
                         const std::vector<unsigned char>& nodes, const BvhTriangles& triangles) {
        s.source = source, s.options = options, s.nodes = nodes, s.triangles = triangles;
    };
    o.on_traced = [&](RayBatchKind kind, const std::vector<BatchRay>& rays, const std::vector<float>& result) {
        s.rays[int(kind)] = rays;
        s.results[int(kind)] = result;
    };
    run_ray_bench(test::device(), scene, o);
    return s;
}

// One batch through the saved program and buffers, as a harness runs it:
// the answers it would write to a ray file.
std::vector<float> retrace(const Saved& s, const BvhTriangles& triangles, RayBatchKind kind) {
    Context& ctx = test::device();
    BuildResult built = build_program(ctx, s.source, s.options);
    const bool any = kind == RayBatchKind::Shadow;
    Kernel k = ctx.kernel(built.program.get(), any ? "batch_trace_any" : "batch_trace_closest");
    const std::vector<BatchRay>& rays = s.rays[int(kind)];
    const auto n = std::uint32_t(rays.size());
    Buffer nodes = test::upload(s.nodes, "nodes"), tris = test::upload(triangles, "triangles");
    Buffer ray_buf = test::upload(rays, "rays");
    Buffer out = ctx.buffer(n * (any ? sizeof(int) : sizeof(Hit)), CL_MEM_READ_WRITE, "answers");
    k.arg(0, nodes).arg(1, tris).arg(2, ray_buf).arg(3, out).arg(4, n);
    test::run(k, n);
    return any ? any_hit_results(test::download<int>(out, n)) : closest_hit_results(test::download<Hit>(out, n));
}

// Bitwise, so that +infinity (a miss) compares equal to itself.
std::size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t d = 0;
    for (std::size_t i = 0; i < a.size(); ++i) d += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
    return d;
}

TEST(RayBatchStructure, SavedProgramAndBuffersGiveTheSavedAnswers) {
    const Saved s = run_and_save();
    ASSERT_NE(s.source.find("kernel void batch_trace_closest"), std::string::npos);
    ASSERT_FALSE(s.nodes.empty());
    ASSERT_FALSE(s.triangles.empty());
    for (RayBatchKind kind : {RayBatchKind::Primary, RayBatchKind::Shadow, RayBatchKind::Diffuse}) {
        SCOPED_TRACE(ray_file_name(kind));
        ASSERT_EQ(s.rays[int(kind)].size(), 32u * 24u * CLP_BATCH_SAMPLES);
        EXPECT_EQ(differing(retrace(s, s.triangles, kind), s.results[int(kind)]), 0u);
    }
}

// Control: the comparison sees the buffers. The same program over the
// triangles in reverse order (the nodes now name other triangles) answers
// differently.
TEST(RayBatchStructure, ControlOtherTrianglesGiveOtherAnswers) {
    const Saved s = run_and_save();
    BvhTriangles reversed(s.triangles.rbegin(), s.triangles.rend());
    EXPECT_GT(differing(retrace(s, reversed, RayBatchKind::Primary), s.results[int(RayBatchKind::Primary)]), 100u);
}

RayBenchResult run_variant(const std::vector<std::pair<std::string, std::string>>& files,
                           const std::string& options = "") {
    const Scene scene = load_scene("cornell");
    RayBenchOptions o;
    o.width = 32, o.height = 24, o.launches = 3, o.embree = false;
    o.ab.files = files;
    o.ab.options = options;
    return run_ray_bench(test::device(), scene, o);
}

TEST(RayBatchVariant, SameKernelsTimedInTurnGiveTheSameAnswers) {
    const RayBenchResult r = run_variant({{"traverse.cl", embedded_source("traverse.cl")}});
    ASSERT_EQ(r.batches.size(), 3u);
    for (const BatchResult& b : r.batches) {
        SCOPED_TRACE(b.name);
        ASSERT_TRUE(b.ab.ran);
        EXPECT_EQ(b.ab.ratios.size(), 3u);  // one per timed launch
        EXPECT_EQ(b.launch_ms.size(), 3u);
        for (double x : b.ab.ratios) EXPECT_GT(x, 0.0);
        EXPECT_LE(b.ab.q1, b.ab.median);
        EXPECT_LE(b.ab.median, b.ab.q3);
        EXPECT_EQ(b.ab.differing, 0u);
        EXPECT_FALSE(describe_ab(b).empty());
    }
}

// intersect.cl with code put in the triangle test after the edge functions.
std::string intersect_with(const std::string& code) {
    std::string text = embedded_source("intersect.cl");
    const std::size_t at = text.find("float det = U + V + W;");
    if (at == std::string::npos) throw std::logic_error("intersect.cl no longer has the line this test edits");
    return text.insert(at, code);
}

// Control: a variant whose triangle test never hits answers differently for
// every ray that hit (all primaries in the closed box).
TEST(RayBatchVariant, ControlAVariantThatNeverHitsDiffers) {
    const RayBenchResult r = run_variant({{"intersect.cl", intersect_with("return 0; ")}});
    const BatchResult& primary = r.batches[0];
    ASSERT_TRUE(primary.ab.ran);
    EXPECT_GT(primary.hits, 0u);
    EXPECT_EQ(primary.ab.differing, primary.hits);
    EXPECT_EQ(primary.agreement.mismatched, 0u);  // the built-in kernels' answers are still the ones checked
}

// The variant's options reach its program, and only it: a define that stops
// the variant's triangle test makes it differ on every hit; without it, or
// given to nothing but the built-in kernels' text, nothing differs.
TEST(RayBatchVariant, OptionsReachTheVariant) {
    const std::string text = intersect_with("\n#ifdef CLP_TEST_NEVER_HIT\nreturn 0;\n#endif\n");
    const RayBenchResult stopped = run_variant({{"intersect.cl", text}}, "-DCLP_TEST_NEVER_HIT");
    EXPECT_EQ(stopped.batches[0].ab.differing, stopped.batches[0].hits);
    EXPECT_GT(stopped.batches[0].hits, 0u);
    const RayBenchResult plain = run_variant({{"intersect.cl", text}});
    for (const BatchResult& b : plain.batches) EXPECT_EQ(b.ab.differing, 0u) << b.name;
    // Options alone make a variant too.
    const RayBenchResult options_only = run_variant({}, "-DCLP_TEST_NEVER_HIT");
    for (const BatchResult& b : options_only.batches) {
        EXPECT_TRUE(b.ab.ran) << b.name;
        EXPECT_EQ(b.ab.differing, 0u) << b.name;  // the built-in files do not read the define
    }
}

TEST(RayBatchVariant, AFileThatIsNotAKernelFileIsNamed) {
    try {
        run_variant({{"traversal.cl", "kernel void x() {}"}});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("traversal.cl is not one of clpath's kernel files"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace clpath
