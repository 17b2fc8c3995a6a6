// White furnace: inside a closed sphere of albedo a that emits Le everywhere,
// every path gathers Le (1 + a + a^2 + ...), so every pixel's expectation is
// Le (1 - a^(n+1)) / (1 - a) for paths of at most n bounces. The image mean
// must match within the standard error that the image's own pixels give
// (pixels are independent estimates of the same value).
#include <gtest/gtest.h>

#include <cmath>

#include "support/analytic_scenes.hpp"
#include "support/render_helpers.hpp"
#include "support/statistics.hpp"

using namespace clpath;

namespace {

Scene furnace(glm::vec3 albedo, glm::vec3 le) {
    Scene s = test::furnace_sphere(albedo, le);
    s.camera.width = s.camera.height = 24;
    return s;
}

void check_furnace(std::uint32_t rr_rule, std::uint32_t max_depth, std::uint32_t integrator,
                   std::uint32_t hemisphere = kHemisphereCosine) {
    SCOPED_TRACE(integrator_name(integrator));
    SCOPED_TRACE(hemisphere_name(hemisphere));
    const glm::vec3 albedo(0.5f, 0.8f, 0.9f), le(1.0f, 0.5f, 0.25f);
    RenderSettings st;
    st.integrator = integrator;
    st.rr_rule = rr_rule;
    st.max_depth = max_depth;
    st.hemisphere = hemisphere;
    st.seed = 17;
    RenderStats stats;
    const auto img = test::render(furnace(albedo, le), st, 64, &stats).linear;
    EXPECT_EQ(stats.nonfinite, 0u);
    // Three channels, each tested at alpha = 1e-4 / 3 (Bonferroni).
    const double z = test::normal_quantile_two_sided(1e-4 / 3);
    for (int c = 0; c < 3; ++c) {
        const double a = albedo[c];
        // The thesis rule stops every path after max_depth - 1 bounces at most.
        const int bounces = rr_rule == CLP_RR_DEPTH ? int(max_depth) - 1 : int(max_depth);
        const double expected = test::furnace_radiance(le[c], a, bounces);
        const auto m = test::mean_error(test::channel(img, c));
        // Without roulette, cosine-weighted BSDF sampling gives every path the
        // same value (zero variance): then float rounding bounds the error, about
        // one rounding per operation on the path (gamma(n) of PBR 6.8.1 with n = 4
        // per bounce, plus the mean). Light sampling with MIS, and uniform
        // hemisphere sampling (weight 2 a cos theta), are exact only in
        // expectation: their samples vary, and the mean is tested as usual.
        const double rounding = expected * (4 * (bounces + 2)) * 0x1.0p-24;
        EXPECT_NEAR(m.mean, expected, z * m.std_error + rounding)
            << "channel " << c << " albedo " << a << ": mean " << m.mean << " +- " << m.std_error;
        if (rr_rule == CLP_RR_NONE && integrator == CLP_INTEGRATOR_PATH_BSDF && hemisphere == kHemisphereCosine) {
            EXPECT_LT(m.std_error, rounding);
        }
    }
}

}  // namespace

// Each for both light-transport integrators: BSDF sampling alone, and
// next-event estimation with MIS (every triangle of the shell is a light).
TEST(WhiteFurnace, ThroughputRussianRoulette) {
    for (auto i : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) check_furnace(CLP_RR_THROUGHPUT, 64, i);
}
TEST(WhiteFurnace, ThesisDepthRussianRoulette) {
    for (auto i : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) check_furnace(CLP_RR_DEPTH, 64, i);
}
TEST(WhiteFurnace, NoRussianRouletteShortPaths) {
    for (auto i : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) check_furnace(CLP_RR_NONE, 5, i);
}
// The thesis text's uniform hemisphere sampling, with each roulette rule.
TEST(WhiteFurnace, UniformHemisphere) {
    for (auto i : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) {
        check_furnace(CLP_RR_THROUGHPUT, 64, i, kHemisphereUniform);
        check_furnace(CLP_RR_DEPTH, 64, i, kHemisphereUniform);
        check_furnace(CLP_RR_NONE, 5, i, kHemisphereUniform);
    }
}

TEST(WhiteFurnace, DepthRuleIsBiasedAtTheThesisDepth) {
    // The same check must fail to see a truncation it should see: with the
    // thesis's 10 bounces and albedo 0.9, the truncated mean is far from Le/(1-a).
    const glm::vec3 albedo(0.9f), le(1.0f);
    RenderSettings st;
    st.rr_rule = CLP_RR_DEPTH;
    st.max_depth = 10;
    const auto img = test::render(furnace(albedo, le), st, 64).linear;
    const auto m = test::mean_error(test::channel(img, 0));
    EXPECT_GT(std::fabs(m.mean - 1.0 / (1 - 0.9)), 10 * m.std_error);
}
