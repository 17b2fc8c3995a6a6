#pragma once
// Checks every BSDF gets (tests/kernels/materials_test.cpp and
// gltf_material_test.cpp): sampling and evaluation through the probe
// kernels, the chi-square test of sampling against the pdf, and
// weight = eval / pdf.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "scene/scene.hpp"
#include "support/statistics.hpp"
#include "support/test_device.hpp"

namespace clpath::test::bsdf {

constexpr double kPi = 3.14159265358979323846;

struct Samples {
    std::vector<cl_float4> wi_pdf, weight;
};

// The renderer's kernels with uniform hemisphere sampling for diffuse bounces.
inline cl_program uniform_hemisphere_program() {
    RenderSettings s;
    s.hemisphere = kHemisphereUniform;
    return test::probe_program(s);
}

inline Samples sample(const Material& m, glm::vec3 wo, std::uint32_t n, std::uint32_t seed = 7,
               cl_program program = test::probe_program()) {
    Buffer mb = test::upload(std::vector<Material>{m}, "material");
    Buffer a = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "wi");
    Buffer b = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "weight");
    Kernel k = test::device().kernel(program, "probe_bsdf_sample");
    k.arg(0, mb).arg(1, wo.x).arg(2, wo.y).arg(3, wo.z).arg(4, n).arg(5, seed).arg(6, a).arg(7, b);
    test::run(k, n);
    return {test::download<cl_float4>(a, n), test::download<cl_float4>(b, n)};
}

// (f cos, pdf) for each pair.
inline std::vector<cl_float4> eval(const Material& m, const std::vector<cl_float4>& wo, const std::vector<cl_float4>& wi,
                            cl_program program = test::probe_program()) {
    const auto n = std::uint32_t(wo.size());
    Buffer mb = test::upload(std::vector<Material>{m}, "material");
    Buffer a = test::upload(wo), b = test::upload(wi);
    Buffer out = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "eval");
    Kernel k = test::device().kernel(program, "probe_bsdf_eval");
    k.arg(0, mb).arg(1, n).arg(2, a).arg(3, b).arg(4, out);
    test::run(k, n);
    return test::download<cl_float4>(out, n);
}

inline cl_float4 f4(glm::vec3 v) { return cl_float4{{v.x, v.y, v.z, 0.0f}}; }

inline glm::vec3 from_angle(double theta_deg) {
    const double t = theta_deg * kPi / 180;
    return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

// Chi-square test of the sampled directions against the routine's own pdf,
// integrated over each (theta, phi) cell by the midpoint rule on a sub-grid
// (theta cells rather than cos theta cells resolve narrow lobes near the
// normal). Samples that end the path form one more cell, whose expected share
// is what the pdf misses. Reflective materials are binned over the upper
// hemisphere; with `sphere`, transmitting ones over the whole sphere, on a
// finer sub-grid: refraction compresses the transmitted lobe, and the
// midpoint rule on the coarser grid mis-integrates it.
// sample_fn(wo, n) draws n samples; pdf_fn(wos, wis) evaluates (f cos, pdf).
template <class SampleFn, class PdfFn>
test::ChiSquare chi_square_by(SampleFn sample_fn, PdfFn pdf_fn, double theta_deg, bool sphere) {
    const int nt = sphere ? 40 : 20, nphi = 40, sub = sphere ? 16 : 8;
    const double theta_max = sphere ? kPi : kPi / 2;
    const std::uint32_t n = 200000;
    const glm::vec3 wo = from_angle(theta_deg);
    const Samples s = sample_fn(wo, n);
    std::vector<double> observed(nt * nphi + 1, 0.0);
    for (const auto& w : s.wi_pdf) {
        if (w.s[3] < 0) {
            observed.back() += 1;
            continue;
        }
        const double z = w.s[2], phi = std::atan2(double(w.s[1]), double(w.s[0])) + kPi;
        if (z <= 0 && !sphere) {  // reflection below the surface: must not happen
            ADD_FAILURE() << "sample below the surface";
            continue;
        }
        const double theta = std::acos(std::clamp(z, -1.0, 1.0));
        const int it = std::min(nt - 1, int(theta / theta_max * nt)), ip = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
        observed[it * nphi + ip] += 1;
    }
    // The pdf on the sub-grid: d(omega) = sin(theta) d(theta) d(phi).
    std::vector<cl_float4> wos, wis;
    std::vector<double> area;
    const double dt = theta_max / (nt * sub), dp = 2 * kPi / (nphi * sub);
    for (int it = 0; it < nt * sub; ++it)
        for (int ip = 0; ip < nphi * sub; ++ip) {
            const double theta = (it + 0.5) * dt, phi = (ip + 0.5) * dp - kPi;
            wos.push_back(f4(wo));
            wis.push_back(f4(glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                                       float(std::cos(theta)))));
            area.push_back(std::sin(theta) * dt * dp);
        }
    const auto e = pdf_fn(wos, wis);
    std::vector<double> expected(nt * nphi + 1, 0.0);
    double total = 0;
    for (int it = 0; it < nt * sub; ++it)
        for (int ip = 0; ip < nphi * sub; ++ip) {
            const std::size_t k = std::size_t(it) * nphi * sub + ip;
            const double p = e[k].s[3] * area[k] * n;
            expected[(it / sub) * nphi + ip / sub] += p;
            total += p;
        }
    expected.back() = std::max(0.0, double(n) - total);
    return test::chi_square(observed, expected);
}

inline test::ChiSquare chi_square_of(const Material& m, const Material& pdf_of, double theta_deg, bool sphere = false,
                                     cl_program program = test::probe_program()) {
    return chi_square_by([&](glm::vec3 wo, std::uint32_t n) { return sample(m, wo, n, 7, program); },
                         [&](const std::vector<cl_float4>& wos, const std::vector<cl_float4>& wis) {
                             return eval(pdf_of, wos, wis, program);
                         },
                         theta_deg, sphere);
}

// Sampling m against its own pdf: passes when the p-value exceeds alpha.
inline void chi_square_test(const Material& m, double theta_deg, double alpha, bool sphere = false,
                            cl_program program = test::probe_program()) {
    const test::ChiSquare c = chi_square_of(m, m, theta_deg, sphere, program);
    EXPECT_GT(c.p_value, alpha) << "chi2 " << c.statistic << " dof " << c.dof << " at theta " << theta_deg;
}

// For every non-delta sample, weight = eval / pdf, as one definition must give.
template <class SampleFn, class EvalFn>
void expect_weight_is_eval_over_pdf_by(SampleFn sample_fn, EvalFn eval_fn, glm::vec3 wo) {
    const Samples s = sample_fn(wo, 2000);
    std::vector<cl_float4> wos, wis;
    for (const auto& w : s.wi_pdf)
        if (w.s[3] > 0) {
            wos.push_back(f4(wo));
            wis.push_back(w);
        }
    ASSERT_GT(wis.size(), 1000u) << "most samples must succeed";
    const auto e = eval_fn(wos, wis);
    std::size_t j = 0;
    for (std::size_t i = 0; i < s.wi_pdf.size(); ++i) {
        if (!(s.wi_pdf[i].s[3] > 0)) continue;
        EXPECT_NEAR(e[j].s[3], s.wi_pdf[i].s[3], 1e-4 * s.wi_pdf[i].s[3]);
        for (int c = 0; c < 3; ++c) {
            const double w = e[j].s[c] / e[j].s[3];
            // Both sides are ~50 float operations apart: gamma(256) each, as a relative bound.
            EXPECT_NEAR(s.weight[i].s[c], w, 2 * 256 * 0x1.0p-24 * std::abs(w) + 1e-7);
        }
        ++j;
    }
}

inline void expect_weight_is_eval_over_pdf(const Material& m, glm::vec3 wo, cl_program program = test::probe_program()) {
    expect_weight_is_eval_over_pdf_by([&](glm::vec3 w, std::uint32_t n) { return sample(m, w, n, 7, program); },
                                      [&](const std::vector<cl_float4>& wos, const std::vector<cl_float4>& wis) {
                                          return eval(m, wos, wis, program);
                                      },
                                      wo);
}


}  // namespace clpath::test::bsdf
