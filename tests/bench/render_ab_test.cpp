// bench render-ab (host/bench/render_ab.hpp): the renderer's kernels timed
// against a variant in one process, the two images compared pixel by pixel.
#include <gtest/gtest.h>

#include <string>

#include "bench/render_ab.hpp"
#include "cl/embedded_sources.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

RenderAbResult run(const KernelVariant& variant, std::uint32_t spp = 3) {
    Scene scene = load_scene("cornell");
    scene.camera.width = 32;
    scene.camera.height = 24;
    RenderAbOptions o;
    o.spp = spp;
    o.seed = 5;
    o.variant = variant;
    return run_render_ab(test::device(), scene, o, {});
}

TEST(RenderAb, SameKernelsTimedInTurnGiveTheSameImage) {
    const RenderAbResult r = run({{{"sampling.cl", embedded_source("sampling.cl")}}, ""});
    EXPECT_EQ(r.ab.ratios.size(), 3u);  // one per launch pair
    for (double x : r.ab.ratios) EXPECT_GT(x, 0.0);
    EXPECT_LE(r.ab.q1, r.ab.median);
    EXPECT_LE(r.ab.median, r.ab.q3);
    EXPECT_GT(r.builtin_msamples_per_s, 0.0);
    EXPECT_GT(r.variant_msamples_per_s, 0.0);
    EXPECT_EQ(r.ab.differing, 0u);
    EXPECT_EQ(r.max_abs_diff, 0.0);
    EXPECT_NE(describe_render_ab(r).find("images differ in 0 of 768 pixels"), std::string::npos)
        << describe_render_ab(r);
}

// Control, and the options reach the variant: uniform rather than
// cosine-weighted bounces estimate the same image with other samples, so
// (nearly) every pixel that a bounce reaches differs.
TEST(RenderAb, ControlAVariantThatSamplesOtherwiseDiffers) {
    const RenderAbResult r = run({{}, "-DCLP_UNIFORM_HEMISPHERE"});
    EXPECT_GT(r.ab.differing, 768u / 2);
    EXPECT_GT(r.max_abs_diff, 0.0);
}

TEST(RenderAb, AFileThatIsNotAKernelFileIsNamed) {
    try {
        run({{{"sampler.cl", "kernel void x() {}"}}, ""});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sampler.cl is not one of clpath's kernel files"), std::string::npos)
            << e.what();
    }
}

TEST(RenderAb, NoVariantIsRefused) { EXPECT_THROW(run({}), Error); }

}  // namespace
}  // namespace clpath
