// The BSDFs of kernels/materials.cl, run on the test device: each sampling
// routine against its own pdf (chi-square, as pbrt's chi2 test), sample weights
// against evaluation, reciprocity, GGX energy against a numerical integral, and
// glass against Fresnel's equations and Snell's law.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>

#include <gtest/gtest.h>

#include "scene/scene.hpp"
#include "support/statistics.hpp"
#include "support/test_device.hpp"
#include "bsdf_checks.hpp"

using namespace clpath;
using namespace clpath::test::bsdf;

namespace {

// The sub-grid integration itself has an error; 18 tests share alpha = 1e-3 (Sidak).
const double kAlpha = 1 - std::pow(1 - 1e-3, 1.0 / 18);

}  // namespace

TEST(Materials, DiffuseSamplingMatchesPdf) {
    for (double theta : {0.0, 60.0}) chi_square_test(diffuse(glm::vec3(0.7f)), theta, kAlpha);
}

TEST(Materials, UniformHemisphereDiffuseSamplingMatchesPdf) {
    for (double theta : {0.0, 60.0})
        chi_square_test(diffuse(glm::vec3(0.7f)), theta, kAlpha, false, uniform_hemisphere_program());
}

// The build option does select the other estimator: every pdf is 1/(2 pi), and
// cos theta is uniform on [0, 1] (mean 1/2; cosine weighting gives 2/3).
TEST(Materials, UniformHemisphereIsUniform) {
    const std::uint32_t n = 20000;
    const Samples s = sample(diffuse(glm::vec3(0.7f)), from_angle(30), n, 5, uniform_hemisphere_program());
    std::vector<double> z;
    for (const auto& w : s.wi_pdf) {
        if (w.s[3] < 0) continue;  // a direction exactly in the plane ends the path
        EXPECT_FLOAT_EQ(w.s[3], float(0.5 / kPi));
        z.push_back(w.s[2]);
    }
    const auto m = test::mean_error(z);
    EXPECT_NEAR(m.mean, 0.5, 4.4 * m.std_error);  // alpha 1e-5, two-sided
}

TEST(Materials, ConductorSamplingMatchesPdf) {
    for (float rough : {0.3f, 0.6f, 0.9f})
        for (double theta : {10.0, 70.0}) {
            SCOPED_TRACE(rough);
            chi_square_test(conductor(glm::vec3(0.9f), rough), theta, kAlpha);
        }
}

// With either hemisphere for diffuse bounces.
TEST(Materials, SampleWeightEqualsEvalOverPdf) {
    for (cl_program program : {test::probe_program(), uniform_hemisphere_program()})
        for (const Material& m : {diffuse(glm::vec3(0.5f, 0.6f, 0.7f)), conductor(glm::vec3(0.9f, 0.6f, 0.3f), 0.5f)})
            expect_weight_is_eval_over_pdf(m, from_angle(40), program);
    // Rough glass from outside and from inside, tinted.
    for (double theta : {40.0, 180.0 - 30.0})
        expect_weight_is_eval_over_pdf(dielectric(1.5f, 0.5f, glm::vec3(0.9f, 0.8f, 0.7f)), from_angle(theta));
}

TEST(Materials, RoughGlassSamplingMatchesPdf) {
    for (float rough : {0.3f, 0.7f})
        for (double theta : {20.0, 70.0, 180.0 - 20.0, 180.0 - 60.0}) {
            SCOPED_TRACE(rough);
            chi_square_test(dielectric(1.5f, rough), theta, kAlpha, true);
        }
}

// Rough glass from either side: the mean sample weight (its directional
// albedo) never exceeds 1 (z = 4.4 over the standard error), and for a
// nearly smooth surface it is nearly 1 (single-scattering GGX loses a little
// to masking, under 2 % at roughness 0.1: Walter et al. 2007's figures).
TEST(Materials, RoughGlassNeverCreatesEnergy) {
    for (float rough : {0.1f, 0.5f, 0.9f})
        for (double theta : {0.0, 50.0, 80.0, 180.0 - 20.0, 180.0 - 60.0}) {
            const Samples s = sample(dielectric(1.5f, rough), from_angle(theta), 200000);
            // Energy, not radiance: undo the 1/eta^2 radiance scaling of transmitted samples.
            const glm::vec3 wo = from_angle(theta);
            const double eta = wo.z > 0 ? 1.5 : 1 / 1.5;
            std::vector<double> w;
            for (std::size_t i = 0; i < s.weight.size(); ++i)
                w.push_back(s.weight[i].s[0] * (s.wi_pdf[i].s[2] * wo.z < 0 ? eta * eta : 1.0));
            const auto m = test::mean_error(w);
            EXPECT_LE(m.mean, 1.0 + 4.4 * m.std_error) << "roughness " << rough << " theta " << theta;
            if (rough < 0.2f && theta < 60) {
                EXPECT_GT(m.mean, 0.98) << "roughness " << rough << " theta " << theta;
            }
        }
}

namespace {
double fresnel(double cos_i, double eta) {
    const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin2_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t), rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rp * rp + rs * rs);
}

// Walter et al. 2007's rough-glass transmission f(wo, wi) in double, written
// out here: wo and wi on opposite sides, e = n(wi side) / n(wo side), with
// the 1/e^2 radiance scaling; 0 where the half vector's microfacet faces away.
double rough_glass_transmission(glm::dvec3 wo, glm::dvec3 wi, double alpha, double e) {
    glm::dvec3 h = glm::normalize(wo + e * wi);
    if (h.z * wo.z < 0) h = -h;  // the microfacet normal on wo's side
    if (glm::dot(wo, h) <= 0 || glm::dot(wi, h) >= 0) return 0;  // back-facing microfacet
    const double wo_h = std::abs(glm::dot(wo, h)), wi_h = std::abs(glm::dot(wi, h));
    const double a2 = alpha * alpha, c2 = h.z * h.z, dd = c2 * (a2 - 1) + 1, D = a2 / (kPi * dd * dd);
    auto lambda = [&](double z) { return 0.5 * (std::sqrt(1 + a2 * (1 - z * z) / (z * z)) - 1); };
    const double G = 1 / (1 + lambda(wo.z) + lambda(wi.z)), F = fresnel(wo_h, e);
    const double denom = wo_h - e * wi_h;  // wo.h and wi.h have opposite signs
    return (1 - F) * D * G * wi_h * wo_h / (std::abs(wo.z * wi.z) * denom * denom);
}
}  // namespace

// Rough glass obeys the generalised reciprocity of a BTDF that scales
// radiance by 1/eta^2: f(wo, wi) / n(wo)^2 = f(wi, wo) / n(wi)^2, and plain
// reciprocity for reflection (Veach 1997, 5.2).
TEST(Materials, RoughGlassReciprocity) {
    const float ior = 1.5f, rough = 0.5f;
    const Material glass = dielectric(ior, rough);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, 1);
    auto dir = [&](bool up) {
        const float z = 0.1f + 0.9f * u(rng), phi = float(2 * kPi) * u(rng), r = std::sqrt(1 - z * z);
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), up ? z : -z);
    };
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        a.push_back(f4(dir(i % 2 == 0)));
        b.push_back(f4(dir(i % 4 < 2)));
    }
    const auto ab = eval(glass, a, b), ba = eval(glass, b, a);
    int transmitted = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 wa(a[i].s[0], a[i].s[1], a[i].s[2]), wb(b[i].s[0], b[i].s[1], b[i].s[2]);
        const double na = wa.z > 0 ? 1.0 : ior, nb = wb.z > 0 ? 1.0 : ior;
        const double f1 = ab[i].s[0] / std::abs(wb.z) / (na * na), f2 = ba[i].s[0] / std::abs(wa.z) / (nb * nb);
        // About 60 roundings on each side, gamma(512) as for the reflective
        // BSDFs. Transmission is worse conditioned (Fresnel near the critical
        // angle, the generalised half vector, the lobe's steep tail): its
        // rounding acts like perturbing the inputs by a few dozen ulps (off
        // unit length too: near grazing on the microfacet, Fresnel from the
        // two sides differs by 1e-3 for float-rounded unit vectors), so the
        // bound adds f's response, in double, to 64-ulp input perturbations.
        double response = 0;
        if (wa.z * wb.z < 0) {
            ++transmitted;
            const double f = rough_glass_transmission(wa, wb, double(rough) * rough, nb / na) / (na * na);
            std::mt19937 prng(i);
            std::uniform_real_distribution<double> d(-64 * 0x1.0p-24, 64 * 0x1.0p-24);
            for (int k = 0; k < 4; ++k) {
                const glm::dvec3 pa = wa + glm::dvec3(d(prng), d(prng), d(prng)), pb = wb + glm::dvec3(d(prng), d(prng), d(prng));
                const double fp = rough_glass_transmission(pa, pb, double(rough) * rough, nb / na) / (na * na);
                const double fq = rough_glass_transmission(pb, pa, double(rough) * rough, na / nb) / (nb * nb);
                response = std::max({response, std::abs(fp - f), std::abs(fq - f)});
            }
            EXPECT_NEAR(f1, f, 512 * 0x1.0p-24 * f + 2 * response + 1e-9)
                << "pair " << i << ": kernel against Walter et al. in double";
        }
        EXPECT_NEAR(f1, f2, 512 * 0x1.0p-24 * std::max(f1, f2) + 2 * response + 1e-9)
            << "pair " << i << std::setprecision(9) << " wo " << wa.x << " " << wa.y << " " << wa.z << " wi " << wb.x << " " << wb.y << " " << wb.z;
    }
    EXPECT_GT(transmitted, 500) << "the pairs must exercise both lobes";
}

// Directional albedo of a GGX conductor with F = 1, by quadrature in double
// with formulas written out here (Walter et al. 2007; Heitz 2014).
double ggx_albedo(double alpha, double theta_o) {
    auto lambda = [&](double cos_t) {
        const double t2 = (1 - cos_t * cos_t) / (cos_t * cos_t);
        return 0.5 * (std::sqrt(1 + alpha * alpha * t2) - 1);
    };
    const double wo[3] = {std::sin(theta_o), 0, std::cos(theta_o)};
    const int nt = 800, np = 800;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double z = (i + 0.5) / nt;
        for (int j = 0; j < np; ++j) {
            const double phi = (j + 0.5) / np * 2 * kPi, r = std::sqrt(1 - z * z);
            const double wi[3] = {r * std::cos(phi), r * std::sin(phi), z};
            double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
            const double hl = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            const double hz = h[2] / hl;
            const double a2 = alpha * alpha, d = hz * hz * (a2 - 1) + 1;
            const double D = a2 / (kPi * d * d);
            const double G = 1 / (1 + lambda(wo[2]) + lambda(z));
            sum += D * G / (4 * wo[2]) * (1.0 / nt) * (2 * kPi / np);  // f cos_i d(omega), f = DG/(4 cos_o cos_i)
        }
    }
    return sum;
}

TEST(Materials, GgxEnergyLossMatchesItsIntegral) {
    for (float rough : {0.5f, 0.9f})
        for (double theta : {0.0, 60.0}) {
            const double alpha = double(rough) * rough;
            const Samples s = sample(conductor(glm::vec3(1.0f), rough), from_angle(theta), 400000);
            std::vector<double> w;
            for (const auto& x : s.weight) w.push_back(x.s[0]);  // failed samples weigh 0
            const auto m = test::mean_error(w);
            const double expected = ggx_albedo(alpha, theta * kPi / 180);
            EXPECT_LE(expected, 1.0);
            EXPECT_LE(m.mean, 1.0 + 4.4 * m.std_error) << "GGX must never create energy";
            // alpha 1e-5 two-sided (z = 4.4), plus the quadrature's own error (< 1e-3 on this grid).
            EXPECT_NEAR(m.mean, expected, 4.4 * m.std_error + 1e-3)
                << "roughness " << rough << " theta " << theta << ": " << m.mean << " +- " << m.std_error;
            if (rough > 0.8f) {
                EXPECT_LT(expected, 0.95);
            }  // rough GGX does lose energy: multiple scattering is not modelled
        }
}

TEST(Materials, MirrorReflectsExactly) {
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, -0.4f, 0.8f));
    const Samples s = sample(mirror(glm::vec3(0.9f, 0.8f, 0.7f)), wo, 64);
    for (std::size_t i = 0; i < 64; ++i) {
        EXPECT_FLOAT_EQ(s.wi_pdf[i].s[0], -wo.x);
        EXPECT_FLOAT_EQ(s.wi_pdf[i].s[1], -wo.y);
        EXPECT_FLOAT_EQ(s.wi_pdf[i].s[2], wo.z);
        EXPECT_FLOAT_EQ(s.weight[i].s[0], 0.9f);
        EXPECT_EQ(s.weight[i].s[3], 1.0f);  // delta
    }
}


// From outside (wo.z > 0) and inside: the reflected share is Fresnel's
// reflectance (binomial tolerance), refraction obeys Snell's law, radiance is
// scaled by 1/eta^2, and beyond the critical angle everything reflects.
TEST(Materials, GlassFollowsFresnelAndSnell) {
    const float ior = 1.5f;
    const Material glass = dielectric(ior);
    for (double theta : {0.0, 30.0, 60.0, 85.0, 180.0 - 30.0, 180.0 - 40.0, 180.0 - 60.0}) {
        const glm::vec3 wo = from_angle(theta);
        const bool outside = wo.z > 0;
        const double eta = outside ? ior : 1.0 / ior;
        const double F = fresnel(std::abs(wo.z), eta);
        const std::uint32_t n = 100000;
        const Samples s = sample(glass, wo, n);
        double reflected = 0;
        const double sin_i = std::sqrt(1 - double(wo.z) * wo.z);
        for (std::uint32_t i = 0; i < n; ++i) {
            const auto& w = s.wi_pdf[i];
            ASSERT_GE(w.s[3], 0) << "glass never ends a path";
            EXPECT_EQ(s.weight[i].s[3], 1.0f);
            if ((w.s[2] > 0) == outside) {
                reflected += 1;
                EXPECT_FLOAT_EQ(s.weight[i].s[0], 1.0f);
                EXPECT_NEAR(w.s[2], wo.z, 1e-6);
            } else {
                const double sin_t = std::sqrt(double(w.s[0]) * w.s[0] + double(w.s[1]) * w.s[1]);
                EXPECT_NEAR(sin_t * eta, sin_i, 1e-5) << "Snell";
                EXPECT_NEAR(s.weight[i].s[0], 1.0 / (eta * eta), 1e-6);
            }
        }
        const double share = reflected / n, sd = std::sqrt(F * (1 - F) / n);
        EXPECT_NEAR(share, F, 4.4 * sd + 1.0 / n) << "theta " << theta;
    }
    // Inside, beyond the critical angle asin(1/1.5) = 41.8 degrees: total internal reflection.
    const Samples tir = sample(glass, from_angle(180.0 - 50.0), 1000);
    for (const auto& w : tir.wi_pdf) EXPECT_LT(w.s[2], 0.0f);
}
