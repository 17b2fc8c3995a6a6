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
// counter is 32-bit and launches are sized below it; the sample index is
// 32-bit and the renderer refuses to go past it (with a message).
TEST(Accumulation, CounterWidths) {
    static_assert(std::is_same_v<decltype(RenderStats::samples_per_pixel), std::uint64_t>);
    static_assert(std::is_same_v<decltype(RenderStats::rays), std::uint64_t>);
    static_assert(std::is_same_v<decltype(RenderStats::nonfinite), std::uint64_t>);
    static_assert(sizeof(Counters::rays) == 4 && sizeof(FrameParams::first_sample) == 4);
    static_assert(kMaxSamplesPerPixel == 0xffffffffull, "sample indices are 32-bit in the kernels");
    // The ray bound per sample holds for the path integrator at its worst
    // (every bounce hits, every bounce traces a shadow ray).
    RenderSettings st;
    st.max_depth = 1024;
    EXPECT_EQ(max_rays_per_sample(st), 2050u);
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
