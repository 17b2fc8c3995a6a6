// Accumulation (robustness suite, item 7): a million samples per pixel of a
// constant-radiance scene stay exact within float's error bound, and the
// sample and ray counters cannot overflow in any run a user can start.
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "scene/shapes.hpp"
#include "support/render_helpers.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

// The camera sees nothing but the inside of an emitting, non-reflecting box:
// every sample is exactly Le (max depth 0: the camera ray only).
Scene glowing_box(glm::vec3 le) {
    Scene s;
    s.name = "glow";
    s.add_triangles(transformed(make_box(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(4))),
                    s.add_material("glow", emitter(le, true)));
    s.camera.eye = {0.1f, 0.2f, 0};
    s.camera.target = {1, 0.3f, 0.2f};
    s.camera.width = s.camera.height = 4;
    return s;
}

}  // namespace

// 10^6 samples of the value 0.1f (not a dyadic number: every addition
// rounds). A naive float sum would be off by percents (past 2^17 the sum's ulp
// is 1/64 of a sample); the Kahan-compensated film (Kahan 1965) has error
// <= 2u sum|x| + O(n u^2) (Higham, Accuracy and Stability, 4.3), and the
// resolve adds three roundings (sum - comp, the float 1/n, the product):
// |mean - Le| <= 5u Le + 10^6 u^2 Le, with u = 2^-24.
TEST(Accumulation, MillionSamplesOfConstantRadianceStayExact) {
    const glm::vec3 le(0.1f, 0.7f, 3.3f);
    RenderSettings st;
    st.max_depth = 0;
    st.rr_rule = CLP_RR_NONE;
    RenderStats stats;
    const std::uint32_t n = 1'000'000;
    const auto img = test::render(glowing_box(le), st, n, &stats).linear;
    EXPECT_EQ(stats.samples_per_pixel, n);
    EXPECT_EQ(stats.nonfinite, 0u);
    EXPECT_GT(stats.launches, 1u) << "the samples should be split into several launches";
    const double u = 0x1.0p-24;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        const double expected = le[int(i % 3)];
        EXPECT_NEAR(img.rgb[i], expected, (5 * u + 1e6 * u * u) * expected) << "value " << i;
    }
}

// Counter widths: the host's totals are 64-bit; the kernels' per-launch ray
// counter and sample index are 32-bit (a launch's rays are kept below 2^32 by
// Accumulation.LaunchesKeepTheRayCounterBelow32Bits, the index by
// Accumulation.SampleCountBeyondTheIndexIsRefused).
static_assert(std::is_same_v<decltype(RenderStats::samples_per_pixel), std::uint64_t>);
static_assert(std::is_same_v<decltype(RenderStats::rays), std::uint64_t>);
static_assert(std::is_same_v<decltype(RenderStats::nonfinite), std::uint64_t>);
static_assert(sizeof(Counters::rays) == 4 && sizeof(FrameParams::first_sample) == 4);
static_assert(kMaxSamplesPerPixel == 0xffffffffull, "sample indices are 32-bit in the kernels");

namespace {
// A closed box with a point light inside, seen from inside: every camera ray
// and every bounce hits, and the light is in front of every surface, so
// next-event estimation traces a shadow ray at every bounce. Both tests below
// render it at max_depth 1024 (one kernel build).
Scene lit_closed_box() {
    Scene s;
    s.name = "lit-box";
    s.add_triangles(transformed(make_box(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(4))),
                    s.add_material("grey", diffuse(glm::vec3(0.5f))));
    PunctualLight bulb;
    bulb.position = {0, -0.5f, 0.3f};
    bulb.intensity = glm::vec3(1.0f);
    s.lights = {bulb};
    s.camera.eye = {0.1f, 0.2f, 0};
    s.camera.target = {1, 0.3f, 0.2f};
    s.camera.width = 16;
    s.camera.height = 8;
    return s;
}

RenderSettings deep_paths() {
    RenderSettings st;
    st.max_depth = 1024;
    st.rr_rule = CLP_RR_NONE;
    return st;
}
}  // namespace

// The renderer sizes launches by max_rays_per_sample; the integrators at
// their worst must stay within it. Measured: a path of max_depth bounces,
// without roulette, traces its camera ray, one ray per bounce and one shadow
// ray at every vertex but the last (2 max_depth + 1) in a program that can
// see emission (every feature compiled in, the worst case); the box's own
// program, lit by a point light alone, does not trace the ray to the last
// vertex (kernels/path.cl path_next_ray_gathers: 2 max_depth). Ambient
// occlusion traces its camera ray and one occlusion ray (2, the bound at
// max_depth 0).
TEST(Accumulation, WorstCaseRaysPerSampleWithinTheBound) {
    const Scene s = lit_closed_box();
    const std::uint64_t samples = 16ull * 8 * 4;
    RenderSettings st = deep_paths();
    RenderStats stats;
    test::render(s, st, 4, &stats);
    EXPECT_EQ(stats.rays, samples * 2 * st.max_depth);
    EXPECT_LE(stats.rays, samples * max_rays_per_sample(st));
    st.all_features = true;
    test::render(s, st, 4, &stats);
    EXPECT_EQ(stats.rays, samples * (2 * st.max_depth + 1));
    EXPECT_LE(stats.rays, samples * max_rays_per_sample(st));
    st.all_features = false;
    st.integrator = CLP_INTEGRATOR_AO;
    st.max_depth = 0;
    test::render(s, st, 4, &stats);
    EXPECT_EQ(stats.rays, samples * 2);
    EXPECT_LE(stats.rays, samples * max_rays_per_sample(st));
}

// Launches are sized so that no launch's 32-bit ray counter can pass 2^32 - 1
// at max_rays_per_sample rays per sample: with max_depth 1024 (2050 rays per
// sample) at most 2095138 pixel-samples per launch, whatever the time target
// asks. Seen from outside the box, looking away, every sample traces one ray,
// so the run is cheap, but the renderer must still split it as if every
// sample took the worst path.
TEST(Accumulation, LaunchesKeepTheRayCounterBelow32Bits) {
    Scene s = lit_closed_box();
    s.camera.eye = {0, 5, 0};
    s.camera.target = {0, 6, 0};
    s.camera.up = {0, 0, 1};
    s.camera.width = s.camera.height = 64;
    RenderSettings st = deep_paths();
    st.target_launch_seconds = 1e9;  // the time target alone would take everything in one launch
    const std::uint64_t pixels = 64 * 64, spp = 2048;
    const std::uint64_t per_launch = 0xffffffffull / max_rays_per_sample(st);
    RenderStats stats;
    test::render(s, st, std::uint32_t(spp), &stats);
    EXPECT_EQ(stats.rays, pixels * spp) << "one ray per sample, every one counted";
    // The first launch measures the speed on one sample of every pixel; the
    // rest must take no more than per_launch pixel-samples each.
    const std::uint64_t rest = pixels * (spp - 1);
    EXPECT_GE(stats.launches, 1 + (rest + per_launch - 1) / per_launch);
}

// The first launch is small (16384 pixels), to measure the device; the rest
// of that first pass is sized from the measurement. With a time target no
// launch reaches, one more launch finishes a 256x256 frame, not three more of
// the measuring size (PoCL runs launches that small more slowly per pixel).
TEST(Accumulation, FirstPassGoesOnInLaunchesSizedByTheMeasurement) {
    Scene s = glowing_box(glm::vec3(1));
    s.camera.width = s.camera.height = 256;
    RenderSettings st;
    st.max_depth = 0;
    st.rr_rule = CLP_RR_NONE;
    st.target_launch_seconds = 1e9;
    RenderStats stats;
    const auto img = test::render(s, st, 1, &stats).linear;
    EXPECT_EQ(stats.launches, 2u);
    EXPECT_EQ(stats.rays, 256u * 256u) << "every pixel traced once";
    for (float v : img.rgb) ASSERT_EQ(v, 1.0f) << "every pixel sees the glowing wall";
}

TEST(Accumulation, SampleCountBeyondTheIndexIsRefused) {
    RenderSettings st;
    st.max_depth = 0;
    Renderer r(test::device(), glowing_box(glm::vec3(1)), st);
    r.add_samples(2);
    try {
        r.add_samples(0xffffffffu);
        FAIL() << "4294967297 samples per pixel should be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("4294967295 samples per pixel"), std::string::npos) << e.what();
    }
    EXPECT_EQ(r.stats().samples_per_pixel, 2u) << "a refused request renders nothing";
}

// Rays are counted exactly: with BSDF sampling only, no roulette, inside a
// closed box every path traces exactly max_depth + 1 rays; with next-event
// estimation never more than max_rays_per_sample. Over many launches the
// 64-bit total is the exact sum.
TEST(Accumulation, RaysAreCountedExactly) {
    Scene s;
    s.name = "closed";
    s.add_triangles(transformed(make_box(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(4))),
                    s.add_material("grey", emitter(glm::vec3(0.5f), true, glm::vec3(0.5f))));
    s.camera.eye = {0.1f, 0.2f, 0};
    s.camera.target = {1, 0.3f, 0.2f};
    s.camera.width = 20;
    s.camera.height = 12;
    RenderSettings st;
    st.max_depth = 6;
    st.rr_rule = CLP_RR_NONE;
    st.integrator = CLP_INTEGRATOR_PATH_BSDF;
    st.target_launch_seconds = 1e-4;  // many small launches
    RenderStats stats;
    test::render(s, st, 64, &stats);
    const std::uint64_t samples = 20ull * 12 * 64;
    EXPECT_GT(stats.launches, 2u);
    EXPECT_EQ(stats.rays, samples * (st.max_depth + 1));
    st.integrator = CLP_INTEGRATOR_PATH;
    test::render(s, st, 64, &stats);
    EXPECT_GT(stats.rays, samples * (st.max_depth + 1));
    EXPECT_LE(stats.rays, samples * max_rays_per_sample(st));
}
