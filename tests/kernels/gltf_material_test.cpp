// The glTF metallic-roughness material (kernels/material_gltf.cl) through the
// checks every BSDF gets: sampling against its pdf (chi-square, with a
// control that a wrong pdf is rejected), weight = eval / pdf, reciprocity, the
// white furnace (it never reflects more than arrives, with a control), and
// agreement with a double-precision reference written from the formulas.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "bsdf_checks.hpp"
#include "scene/scene.hpp"
#include "support/statistics.hpp"

using namespace clpath;
using namespace clpath::test::bsdf;

namespace {

// 12 configurations x 2 angles share alpha = 1e-3 (Sidak), as materials_test does.
const double kAlpha = 1 - std::pow(1 - 1e-3, 1.0 / 24);

Material gltf(glm::vec3 base, float metallic, float roughness) { return gltf_material(base, metallic, roughness); }

// The BSDF in double, from the formulas in material_gltf.cl's header comment:
// f cos(theta_i) and the pdf, in the local frame.
struct Ref {
    glm::dvec3 f;
    double pdf;
};
double schlick(double f0, double c) { return f0 + (1 - f0) * std::pow(std::clamp(1 - c, 0.0, 1.0), 5); }
double lum(glm::dvec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
Ref reference(const Material& m, glm::dvec3 wo, glm::dvec3 wi) {
    if (wo.z <= 0 || wi.z <= 0) return {glm::dvec3(0), 0};
    const double a = std::max(double(m.roughness) * m.roughness, 1e-3), a2 = a * a;
    const glm::dvec3 base(m.albedo[0], m.albedo[1], m.albedo[2]);
    const double metal = m.metallic, f0 = std::pow((m.ior - 1.0) / (m.ior + 1.0), 2);
    const glm::dvec3 h = glm::normalize(wo + wi);
    const double d = a2 / (kPi * std::pow(h.z * h.z * (a2 - 1) + 1, 2));
    auto lambda = [&](glm::dvec3 w) { return 0.5 * (std::sqrt(1 + a2 * (1 - w.z * w.z) / (w.z * w.z)) - 1); };
    const double g2 = 1 / (1 + lambda(wo) + lambda(wi)), g1 = 1 / (1 + lambda(wo));
    const double spec = d * g2 / (4 * wo.z * wi.z) * wi.z;
    const double voh = glm::dot(wo, h);
    const glm::dvec3 fc = base + (glm::dvec3(1) - base) * std::pow(1 - voh, 5);
    const glm::dvec3 f = metal * fc * spec +
                         (1 - metal) * (base * ((1 - schlick(f0, wo.z)) * (1 - schlick(f0, wi.z)) / kPi * wi.z) +
                                        glm::dvec3(schlick(f0, voh) * spec));
    const glm::dvec3 fc0 = base + (glm::dvec3(1) - base) * std::pow(1 - wo.z, 5);
    const double ws = metal * lum(fc0) + (1 - metal) * schlick(f0, wo.z);
    const double wd = (1 - metal) * (1 - schlick(f0, wo.z)) * lum(base);
    const double ps = ws + wd > 0 ? ws / (ws + wd) : 1;
    const double pdf = ps * g1 * d / (4 * wo.z) + (1 - ps) * wi.z / kPi;
    return {f, pdf};
}

const std::vector<Material>& configurations() {
    static const std::vector<Material> m = {
        gltf({0.8f, 0.6f, 0.4f}, 0.0f, 0.3f), gltf({0.8f, 0.6f, 0.4f}, 0.0f, 0.8f), gltf({0.9f, 0.7f, 0.3f}, 1.0f, 0.3f),
        gltf({0.9f, 0.7f, 0.3f}, 1.0f, 0.7f), gltf({0.5f, 0.9f, 0.5f}, 0.5f, 0.4f), gltf({0.0f, 0.0f, 0.0f}, 0.0f, 0.5f),
    };
    return m;
}

glm::dvec3 random_dir(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    const double z = u(rng), phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
}

}  // namespace

TEST(GltfMaterial, SamplingMatchesPdf) {
    for (const Material& m : configurations())
        for (double theta : {10.0, 70.0}) {
            SCOPED_TRACE(testing::Message() << "metallic " << m.metallic << " roughness " << m.roughness);
            chi_square_test(m, theta, kAlpha);
        }
}

// Control: the same test rejects sampling checked against a slightly different pdf.
TEST(GltfMaterial, ChiSquareRejectsAWrongPdf) {
    const test::ChiSquare c = chi_square_of(gltf({0.8f, 0.6f, 0.4f}, 0.5f, 0.3f), gltf({0.8f, 0.6f, 0.4f}, 0.5f, 0.36f), 30);
    EXPECT_LT(c.p_value, 1e-6) << "chi2 " << c.statistic << " dof " << c.dof;
}

TEST(GltfMaterial, SampleWeightEqualsEvalOverPdf) {
    for (const Material& m : configurations())
        for (double theta : {0.0, 40.0, 85.0}) expect_weight_is_eval_over_pdf(m, from_angle(theta));
}

// f(wo, wi) = f(wi, wo): eval returns f cos(theta_i), so compare f = eval / cos.
TEST(GltfMaterial, Reciprocity) {
    std::mt19937 rng(3);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 x = random_dir(rng), y = random_dir(rng);
        a.push_back(f4(glm::vec3(x)));
        b.push_back(f4(glm::vec3(y)));
    }
    for (const Material& m : configurations()) {
        const auto ab = eval(m, a, b), ba = eval(m, b, a);
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const double f1 = ab[i].s[c] / b[i].s[2], f2 = ba[i].s[c] / a[i].s[2];
                // ~60 float operations on each side: gamma(128) relative.
                EXPECT_NEAR(f1, f2, 2 * 128 * 0x1.0p-24 * std::max(std::abs(f1), std::abs(f2)) + 1e-7) << i;
            }
    }
}

// Against the double-precision reference, value and pdf.
TEST(GltfMaterial, AgreesWithDoublePrecisionReference) {
    std::mt19937 rng(5);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        a.push_back(f4(glm::vec3(random_dir(rng))));
        b.push_back(f4(glm::vec3(random_dir(rng))));
    }
    for (const Material& m : configurations()) {
        const auto e = eval(m, a, b);
        for (std::size_t i = 0; i < a.size(); ++i) {
            // The reference takes the float directions the kernel saw.
            const Ref r = reference(m, glm::dvec3(a[i].s[0], a[i].s[1], a[i].s[2]), glm::dvec3(b[i].s[0], b[i].s[1], b[i].s[2]));
            // GGX's D near its peak amplifies float rounding of h.z: 1e-4 relative covers
            // gamma(~800) over the ~60 operations, far below any formula error.
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[i].s[c], r.f[c], 1e-4 * std::abs(r.f[c]) + 1e-7) << i;
            EXPECT_NEAR(e[i].s[3], r.pdf, 1e-4 * r.pdf + 1e-7) << i;
        }
    }
}

// The directional albedo (mean sample weight) of a white surface is at most 1:
// the material never creates energy. One-sided test at alpha 1e-6 per case
// (z = 4.75 standard errors).
double albedo_excess(const Material& m, double theta, double scale, double* mean) {
    const Samples s = sample(m, from_angle(theta), 100000, 11);
    std::vector<double> w;
    for (std::size_t i = 0; i < s.weight.size(); ++i)
        w.push_back(s.wi_pdf[i].s[3] > 0 ? scale * s.weight[i].s[1] : 0.0);
    const auto e = test::mean_error(w);
    *mean = e.mean;
    return (e.mean - 1) / std::max(e.std_error, 1e-12);
}

TEST(GltfMaterial, WhiteFurnaceNeverCreatesEnergy) {
    for (float metallic : {0.0f, 0.5f, 1.0f})
        for (float rough : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f})
            for (double theta : {0.0, 45.0, 80.0, 89.0}) {
                double mean;
                const double z = albedo_excess(gltf(glm::vec3(1), metallic, rough), theta, 1.0, &mean);
                EXPECT_LT(z, 4.75) << "metallic " << metallic << " roughness " << rough << " theta " << theta
                                   << ": albedo " << mean;
            }
}

// Control: the same statistic flags a surface that returned 5% more.
TEST(GltfMaterial, WhiteFurnaceRejectsEnergyGain) {
    double mean;
    EXPECT_GT(albedo_excess(gltf(glm::vec3(1), 1.0f, 0.1f), 0.0, 1.05, &mean), 4.75) << mean;
}
