// The Embree path tracer of clpath bench path computes what clpath's renderer
// computes (`render --max-depth D --rr none`): its image agrees with the
// kernels' within the z-score bound of bench/path_agreement.hpp (false
// failure below 1e-6 per check), and the same check rejects a tracer that
// computes something else (a light twice as bright, two bounces fewer).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "bench/embree_path_tracer.hpp"
#include "bench/embree_scene.hpp"
#include "bench/path_agreement.hpp"
#include "render/renderer.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::string scene_file(const std::string& name) {
    return (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "scenes" / (name + ".json")).lexically_normal().string();
}

// Small enough for seconds on two cores; the regions hold 8 x 8 pixels of 64 samples.
Scene tiny(const std::string& name) {
    Scene s = load_scene(scene_file(name));
    s.camera.width = 24;
    s.camera.height = 24;
    return s;
}

constexpr std::uint32_t kSpp = 64;

// clpath's mean image: the path integrator at a fixed depth without roulette, seed 0.
Image clpath_image(const Scene& scene, std::uint32_t depth) {
    RenderSettings settings;
    settings.integrator = CLP_INTEGRATOR_PATH;
    settings.max_depth = depth;
    settings.rr_rule = CLP_RR_NONE;
    settings.seed = 0;
    Renderer r(test::device(), scene, settings);
    r.add_samples(kSpp);
    return r.resolve(1.0f).linear;
}

PathAgreement embree_against(const Image& clpath, const Scene& scene, std::uint32_t depth,
                             EmbreeMode mode = EmbreeMode::Robust) {
    auto tracer = make_embree_path_tracer(scene, depth, mode, 2);
    const EmbreePathRun run = tracer->render(kSpp, 1);  // another stream than clpath's seed 0
    EXPECT_EQ(run.nonfinite, 0u);
    return check_path_agreement(clpath, kSpp, run.sums, 3);
}

#define SKIP_WITHOUT_EMBREE() \
    if (!embree_path_built_in()) GTEST_SKIP() << "built without Embree (CLPATH_WITH_EMBREE off or libembree-dev missing)"

TEST(EmbreePathTracer, PointLightCornellAgreesWithClpath) {
    SKIP_WITHOUT_EMBREE();
    const Scene scene = tiny("cornell-point");
    const Image clpath = clpath_image(scene, 4);
    const PathAgreement same = embree_against(clpath, scene, 4);
    EXPECT_TRUE(same.agrees()) << same.describe();
    // Embree's default mode (not watertight) computes the same estimator.
    const PathAgreement same_default = embree_against(clpath, scene, 4, EmbreeMode::Default);
    EXPECT_TRUE(same_default.agrees()) << same_default.describe();

    // Controls: the same check on a tracer computing something else.
    Scene brighter = scene;
    brighter.lights[0].intensity *= 2.0f;
    const PathAgreement twice = embree_against(clpath, brighter, 4);
    EXPECT_FALSE(twice.agrees()) << "a light twice as bright passed: " << twice.describe();
    const PathAgreement shallow = embree_against(clpath, scene, 2);
    EXPECT_FALSE(shallow.agrees()) << "depth 2 against depth 4 passed: " << shallow.describe();
}

// An area light: light sampling weighted against BSDF sampling by MIS, as the kernels.
TEST(EmbreePathTracer, AreaLightCornellAgreesWithClpath) {
    SKIP_WITHOUT_EMBREE();
    const Scene scene = tiny("cornell-classic");
    const Image clpath = clpath_image(scene, 4);
    const PathAgreement same = embree_against(clpath, scene, 4);
    EXPECT_TRUE(same.agrees()) << same.describe();

    Scene brighter = scene;
    for (auto& m : brighter.materials)
        for (float& e : m.emission) e *= 2.0f;
    const PathAgreement twice = embree_against(clpath, brighter, 4);
    EXPECT_FALSE(twice.agrees()) << "a lamp twice as bright passed: " << twice.describe();
}

// Rays per sample: at depth 0 one camera ray each, exactly; at depth 4 a
// sample traces 1 to 9 rays (camera, 4 bounces, 4 shadow rays), so each
// tracer's mean over n samples has a standard deviation of at most 4 / sqrt(n),
// and the two means (independent streams) may differ by at most 5.33 times
// 4 sqrt(2 / n) (two-sided normal tail 1e-7). Control: Embree at depth 3 traces
// about 1.5 rays per sample fewer.
TEST(EmbreePathTracer, CountsRaysAsTheKernelsDo) {
    SKIP_WITHOUT_EMBREE();
    const Scene scene = tiny("cornell-point");
    auto clpath_rays = [&](std::uint32_t depth) {
        RenderSettings settings;
        settings.max_depth = depth;
        settings.rr_rule = CLP_RR_NONE;
        Renderer r(test::device(), scene, settings);
        r.add_samples(kSpp);
        return r.stats().rays;
    };
    auto embree_rays = [&](std::uint32_t depth) { return make_embree_path_tracer(scene, depth, EmbreeMode::Robust, 2)->render(kSpp, 1).rays; };
    const double n = double(kSpp) * 24 * 24;
    EXPECT_EQ(clpath_rays(0), std::uint64_t(n));
    EXPECT_EQ(embree_rays(0), std::uint64_t(n));
    const double bound = 5.33 * 4.0 * std::sqrt(2.0 / n);
    const double clpath4 = double(clpath_rays(4)) / n;
    EXPECT_LE(std::fabs(double(embree_rays(4)) / n - clpath4), bound);
    EXPECT_GT(std::fabs(double(embree_rays(3)) / n - clpath4), bound) << "depth 3 counted as many rays as depth 4";
}

TEST(EmbreePathTracer, RefusesWhatItCannotRender) {
    // cornell-thesis has a glossy conductor and glass.
    const Scene thesis = load_scene(scene_file("cornell-thesis"));
    const auto why = embree_path_unsupported(thesis);
    std::string all;
    for (const auto& w : why) all += w + "\n";
    EXPECT_NE(all.find("material 'glass' is a dielectric"), std::string::npos) << all;
    EXPECT_NE(all.find("material 'glossy' is a conductor"), std::string::npos) << all;
    EXPECT_TRUE(embree_path_unsupported(tiny("cornell-point")).empty());
    Scene sky = tiny("cornell-point");
    sky.environment.color = glm::vec3(1.0f);
    ASSERT_EQ(embree_path_unsupported(sky).size(), 1u);
    EXPECT_NE(embree_path_unsupported(sky)[0].find("environment"), std::string::npos);
    if (embree_path_built_in()) {
        EXPECT_THROW(make_embree_path_tracer(thesis, 4), Error);
    }
}

// The baselines' tracing threads flush denormals (FTZ) and read them as zero
// (DAZ), as Embree's manual asks, and give the thread its mode back after.
// A subnormal input survives a multiplication by one outside the scope (the
// control) and reads as zero inside it; a product that underflows comes out
// subnormal outside and zero inside.
TEST(EmbreeThreadFloatMode, FlushesDenormalsInsideItsScopeOnly) {
#if defined(__SSE__)
    volatile float subnormal = 1e-39f, one = 1.0f, small = 1e-30f, smaller = 1e-10f;
    ASSERT_EQ(std::fpclassify(subnormal * one), FP_SUBNORMAL);
    ASSERT_EQ(std::fpclassify(small * smaller), FP_SUBNORMAL);
    {
        const EmbreeThreadFloatMode ftz_daz;
        EXPECT_EQ(subnormal * one, 0.0f);  // DAZ
        EXPECT_EQ(small * smaller, 0.0f);  // FTZ
    }
    EXPECT_EQ(std::fpclassify(subnormal * one), FP_SUBNORMAL);
    EXPECT_EQ(std::fpclassify(small * smaller), FP_SUBNORMAL);
#else
    GTEST_SKIP() << "no MXCSR on this CPU: the mode is a no-op here";
#endif
}

// Every field of the ray Embree reads is written, over whatever the memory
// held before (origin and tnear, direction and time go in as two 16-byte
// stores): the offset tnear is (1 + max |o_i|) 1e-6 / |d|.
TEST(EmbreeRay, InitWritesEveryField) {
#if CLPATH_WITH_EMBREE
    RTCRay r;
    std::memset(&r, 0x7f, sizeof r);
    init_embree_ray(r, {1.0f, -3.0f, 2.0f}, {0.0f, 0.0f, 2.0f}, 7.5f);
    EXPECT_EQ(r.org_x, 1.0f);
    EXPECT_EQ(r.org_y, -3.0f);
    EXPECT_EQ(r.org_z, 2.0f);
    EXPECT_EQ(r.tnear, 4.0f * 1e-6f / 2.0f);
    EXPECT_EQ(r.dir_x, 0.0f);
    EXPECT_EQ(r.dir_y, 0.0f);
    EXPECT_EQ(r.dir_z, 2.0f);
    EXPECT_EQ(r.time, 0.0f);
    EXPECT_EQ(r.tfar, 7.5f);
    EXPECT_EQ(r.mask, ~0u);
    EXPECT_EQ(r.id, 0u);
    EXPECT_EQ(r.flags, 0u);
    init_embree_ray(r, {0.5f, 0.25f, -0.5f}, {1.0f, 0.0f, 0.0f}, INFINITY, 1.0f);
    EXPECT_EQ(r.tnear, 1.5f * 1e-6f);
    EXPECT_EQ(r.tfar, INFINITY);
    init_embree_ray(r, {0.5f, 0.25f, -0.5f}, {0.0f, 0.0f, 0.0f}, 1.0f);  // no direction: no offset
    EXPECT_EQ(r.tnear, 0.0f);
#else
    GTEST_SKIP() << "built without Embree (CLPATH_WITH_EMBREE off or libembree-dev missing)";
#endif
}

TEST(PathAgreement, BonferroniBound) {
    // P(|Z| > 4.8916) = 1e-6; with 51 tests each gets 1e-6 / 51.
    EXPECT_NEAR(bonferroni_z_bound(1e-6, 1), 4.8916, 1e-3);
    EXPECT_NEAR(std::erfc(bonferroni_z_bound(1e-6, 51) / std::sqrt(2.0)), 1e-6 / 51, 1e-12);
}

}  // namespace
}  // namespace clpath
