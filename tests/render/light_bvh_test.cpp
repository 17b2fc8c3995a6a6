// The light BVH's host reference (host/render/light_bvh.*): its pmf is a
// distribution, the sampler draws from exactly it, and lights that give
// nothing at a point are never picked.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/light_bvh.hpp"
#include "render/light_table.hpp"
#include "scene/scene.hpp"
#include "support/statistics.hpp"

namespace clpath {
namespace {

constexpr double kAlpha = 1e-7;  // each statistical test's false-failure rate

Light triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 L, bool two_sided) {
    Light l{};
    l.type = CLP_LIGHT_TRIANGLE;
    store3(l.a, a);
    store3(l.b, b);
    store3(l.c, c);
    store3(l.L, L);
    l.flags = two_sided ? CLP_LIGHTF_TWO_SIDED : 0u;
    return l;
}

Light punctual(unsigned type, glm::vec3 pos, glm::vec3 dir, glm::vec3 I) {
    Light l{};
    l.type = type;
    store3(l.a, pos);
    store3(l.b, dir);
    store3(l.L, I);
    l.cos_inner = std::cos(0.3f);
    l.cos_outer = std::cos(0.5f);
    return l;
}

glm::vec3 unit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

// Triangles of every size and orientation, some two-sided and in clusters,
// point and spot lights, a directional light and the environment.
std::vector<Light> mixed_lights(std::mt19937& rng, int triangles) {
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<Light> lights;
    for (int i = 0; i < triangles; ++i) {
        const glm::vec3 c = glm::vec3(u(rng), u(rng), u(rng)) * 10.0f - 5.0f + (i % 3 == 0 ? glm::vec3(20, 0, 0) : glm::vec3(0));
        const float s = 0.02f + u(rng) * (i % 7 == 0 ? 2.0f : 0.2f);
        lights.push_back(triangle(c + s * unit(rng), c + s * unit(rng), c + s * unit(rng),
                                  glm::vec3(u(rng), u(rng), u(rng)) * (i % 11 == 0 ? 100.0f : 1.0f), i % 4 == 0));
    }
    for (int i = 0; i < 8; ++i)
        lights.push_back(punctual(i % 2 ? CLP_LIGHT_SPOT : CLP_LIGHT_POINT, glm::vec3(u(rng), u(rng), u(rng)) * 12.0f - 6.0f,
                                  unit(rng), glm::vec3(u(rng) * 5)));
    Light d{};
    d.type = CLP_LIGHT_DIRECTIONAL;
    store3(d.b, glm::vec3(0, -1, 0));
    store3(d.L, glm::vec3(1));
    lights.push_back(d);
    Light e{};
    e.type = CLP_LIGHT_ENVIRONMENT;
    lights.push_back(e);
    return lights;
}

// The probability that the descent from node i stops with nothing (both
// children of zero importance), computed by expanding the whole tree.
double lost_mass(const LightBvh& bvh, std::uint32_t i, glm::vec3 p, glm::vec3 n) {
    const LightBvhNode& node = bvh.nodes[i];
    if (node.flags & CLP_LIGHT_BVH_LEAF)
        return i == 0 && !(light_bounds_importance(decode_light_bounds(bvh, node), p, n) > 0) ? 1.0 : 0.0;
    const std::uint32_t c0 = i + 1, c1 = node.child;
    const double i0 = light_bounds_importance(decode_light_bounds(bvh, bvh.nodes[c0]), p, n);
    const double i1 = light_bounds_importance(decode_light_bounds(bvh, bvh.nodes[c1]), p, n);
    if (i0 == 0 && i1 == 0) return 1.0;
    return i0 / (i0 + i1) * lost_mass(bvh, c0, p, n) + i1 / (i0 + i1) * lost_mass(bvh, c1, p, n);
}

double total_lost(const LightBvh& bvh, glm::vec3 p, glm::vec3 n) {
    if (bvh.nodes.empty()) return bvh.infinite.empty() ? 1.0 : 0.0;
    const double pi = double(bvh.infinite.size()) / double(bvh.infinite.size() + 1);
    return (1 - pi) * lost_mass(bvh, 0, p, n);
}

TEST(LightBvh, EveryFiniteLightHasALeafAndTheTreeIsShallow) {
    std::mt19937 rng(1);
    const auto lights = mixed_lights(rng, 3000);
    const LightBvh bvh = build_light_bvh(lights);
    EXPECT_EQ(bvh.nodes.size(), 2 * (lights.size() - 2) - 1);
    EXPECT_EQ(bvh.infinite.size(), 2u);
    for (std::size_t i = 0; i + 2 < lights.size(); ++i) EXPECT_NE(bvh.trail[i], 0u) << i;
    EXPECT_LE(bvh.depth, 40);
}

TEST(LightBvh, PmfsSumToOneLessWhatTheDescentLoses) {
    std::mt19937 rng(2);
    const auto lights = mixed_lights(rng, 500);
    const LightBvh bvh = build_light_bvh(lights);
    std::uniform_real_distribution<float> u(-8, 8);
    // Each pmf is a product of at most depth + 1 rounded quotients.
    const double tol = 4.0 * (bvh.depth + 2) * std::ldexp(1.0, -24);
    for (int k = 0; k < 200; ++k) {
        const glm::vec3 p(u(rng), u(rng), u(rng));
        const glm::vec3 n = k % 5 == 0 ? glm::vec3(0) : unit(rng);
        double sum = 0;
        for (std::uint32_t l = 0; l < lights.size(); ++l) sum += light_bvh_pmf(bvh, p, n, l);
        EXPECT_NEAR(sum + total_lost(bvh, p, n), 1.0, tol) << "point " << k;
    }
}

// Counts of picks (the last cell: none) from n independent uniform u.
std::vector<double> sample_counts(const LightBvh& bvh, std::size_t nlights, glm::vec3 p, glm::vec3 n, int count,
                                  std::mt19937& rng) {
    std::vector<double> c(nlights + 1, 0.0);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < count; ++i) {
        const auto s = sample_light_bvh(bvh, p, n, u(rng));
        ++c[s ? s->light : nlights];
    }
    return c;
}

std::vector<double> expected_counts(const LightBvh& bvh, std::size_t nlights, glm::vec3 p, glm::vec3 n, int count) {
    std::vector<double> e(nlights + 1);
    for (std::uint32_t l = 0; l < nlights; ++l) e[l] = count * double(light_bvh_pmf(bvh, p, n, l));
    e[nlights] = count * total_lost(bvh, p, n);
    return e;
}

TEST(LightBvh, SampledFrequenciesMatchThePmf) {
    std::mt19937 rng(3);
    const auto lights = mixed_lights(rng, 120);
    const LightBvh bvh = build_light_bvh(lights);
    const int count = 400000;
    for (const glm::vec3 p : {glm::vec3(0.5f, 0.2f, -1.0f), glm::vec3(18, 3, 1), glm::vec3(-7, 7, 7)}) {
        const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 1, 0.2f));
        const auto obs = sample_counts(bvh, lights.size(), p, n, count, rng);
        const auto chi = test::chi_square(obs, expected_counts(bvh, lights.size(), p, n, count));
        EXPECT_GT(chi.p_value, kAlpha) << "chi2 " << chi.statistic << " dof " << chi.dof;
    }
}

// The control: the same test rejects the power-proportional pmf (the light
// table's) as the sampler's distribution.
TEST(LightBvh, ChiSquareRejectsTheWrongPmf) {
    std::mt19937 rng(3);
    const auto lights = mixed_lights(rng, 120);
    const LightBvh bvh = build_light_bvh(lights);
    const int count = 400000;
    const glm::vec3 p(0.5f, 0.2f, -1.0f), n = glm::normalize(glm::vec3(0.3f, 1, 0.2f));
    const auto obs = sample_counts(bvh, lights.size(), p, n, count, rng);
    std::vector<double> power(lights.size(), 0.0);
    for (std::size_t l = 0; l < lights.size(); ++l) power[l] = std::max(luminance(load3(lights[l].L)), 1e-3);
    double total = 0;
    for (double w : power) total += w;
    std::vector<double> wrong(lights.size() + 1, 0.0);
    for (std::size_t l = 0; l < lights.size(); ++l) wrong[l] = count * power[l] / total;
    EXPECT_LT(test::chi_square(obs, wrong).p_value, kAlpha);
    // A subtler wrong answer: the right pmf with the most likely light's
    // probability moved by a tenth onto the next.
    auto near = expected_counts(bvh, lights.size(), p, n, count);
    std::size_t top = 0;
    for (std::size_t l = 0; l < lights.size(); ++l)
        if (near[l] > near[top]) top = l;
    const double shift = 0.1 * near[top];
    near[top] -= shift;
    near[(top + 1) % lights.size()] += shift;
    EXPECT_LT(test::chi_square(obs, near).p_value, kAlpha);
}

// Stratified u: each light's share of [0, 1) is the pmf its trail gives, and
// the sampler reports that very pmf.
TEST(LightBvh, TrailPmfIsThePickProbability) {
    std::mt19937 rng(4);
    const auto lights = mixed_lights(rng, 60);
    const LightBvh bvh = build_light_bvh(lights);
    const int count = 1 << 20;
    std::uniform_real_distribution<float> u(-8, 8);
    for (int k = 0; k < 4; ++k) {
        const glm::vec3 p(u(rng), u(rng), u(rng)), n = unit(rng);
        std::vector<double> c(lights.size(), 0.0);
        for (int i = 0; i < count; ++i) {
            const auto s = sample_light_bvh(bvh, p, n, (float(i) + 0.5f) / float(count));
            if (!s) continue;
            ++c[s->light];
            ASSERT_EQ(s->pmf, light_bvh_pmf(bvh, p, n, s->light));
        }
        // Each light's u form an interval, up to the rescaled u's rounding.
        const double tol = 3.0 / count + 8.0 * (bvh.depth + 2) * std::ldexp(1.0, -24);
        for (std::uint32_t l = 0; l < lights.size(); ++l)
            EXPECT_NEAR(c[l] / count, light_bvh_pmf(bvh, p, n, l), tol) << "light " << l << " point " << k;
    }
}

TEST(LightBvh, ALightFacingAwayIsNeverPicked) {
    // A one-sided triangle facing +z, the point behind it; others face the point.
    std::vector<Light> lights{triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, glm::vec3(50), false),
                              triangle({3, 0, -2}, {3, 1, -2}, {4, 0, -2}, glm::vec3(1), false),
                              triangle({-3, 0, -2}, {-3, 1, -2}, {-2, 0, -2}, glm::vec3(1), false),
                              punctual(CLP_LIGHT_POINT, {0, 3, -3}, {0, 0, 1}, glm::vec3(1))};
    // (The second and third face -z: cross(b - a, c - a).)
    const LightBvh bvh = build_light_bvh(lights);
    const glm::vec3 p(0.3f, 0.3f, -5.0f), n(0, 0, 1);
    EXPECT_EQ(light_bvh_pmf(bvh, p, n, 0), 0.0f);
    EXPECT_GT(light_bvh_pmf(bvh, p, n, 1), 0.0f);
    EXPECT_GT(light_bvh_pmf(bvh, p, n, 3), 0.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, 1);
    for (int i = 0; i < 100000; ++i) {
        const auto s = sample_light_bvh(bvh, p, n, u(rng));
        ASSERT_TRUE(s);
        ASSERT_NE(s->light, 0u);
    }
    // From in front, it is the most likely light.
    EXPECT_GT(light_bvh_pmf(bvh, {0.3f, 0.3f, 2.0f}, n, 0), 0.5f);
}

}  // namespace
}  // namespace clpath
