// The glTF material's layers (kernels/material_gltf.cl): KHR_materials_clearcoat
// and thin-walled KHR_materials_transmission, through the checks every BSDF
// gets: agreement with a double-precision reference written from the
// formulas, sampling against the pdf over the whole sphere (chi-square, with
// a control that a wrong pdf is rejected), weight = eval / pdf, reciprocity,
// the white furnace (with a control), and that the layers at zero are the
// core material and that a program without transmission gives the same coat.
//
// Deterministic (fixed seeds). The statistical tests' false-failure rates
// are stated where they are made: 1e-6 per run in all.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "bsdf_checks.hpp"
#include "render/kernel_features.hpp"
#include "scene/scene.hpp"
#include "support/statistics.hpp"

using namespace clpath;
using namespace clpath::test::bsdf;

namespace {

struct Layers {
    float clearcoat = 0, coat_roughness = 0, transmission = 0;
    glm::vec3 coat_n{0, 0, 1};
};

struct Case {
    Material m;
    Layers l;
};

// probes.cl compiled with every feature and the layers: both, or the coat alone.
cl_program layered_program(bool transmission = true) {
    SceneFeatures sf;
    sf.clearcoat = true;
    sf.transmission = transmission;
    RenderSettings s;
    s.all_features = true;
    return test::test_program("probes.cl", build_options(kernel_features(sf, s)));
}

cl_float4 layer_params(const Layers& l) { return cl_float4{{l.clearcoat, l.coat_roughness, l.transmission, 0}}; }

Samples layered_sample(const Case& c, glm::vec3 wo, std::uint32_t n, std::uint32_t seed = 7,
                       cl_program program = layered_program()) {
    Buffer mb = test::upload(std::vector<Material>{c.m}, "material");
    Buffer a = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "wi");
    Buffer b = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "weight");
    Kernel k = test::device().kernel(program, "probe_layered_sample");
    k.arg(0, mb).arg(1, layer_params(c.l)).arg(2, f4(c.l.coat_n)).arg(3, wo.x).arg(4, wo.y).arg(5, wo.z).arg(6, n);
    k.arg(7, seed).arg(8, a).arg(9, b);
    test::run(k, n);
    return {test::download<cl_float4>(a, n), test::download<cl_float4>(b, n)};
}

std::vector<cl_float4> layered_eval(const Case& c, const std::vector<cl_float4>& wo, const std::vector<cl_float4>& wi,
                                    cl_program program = layered_program()) {
    const auto n = std::uint32_t(wo.size());
    Buffer mb = test::upload(std::vector<Material>{c.m}, "material");
    Buffer a = test::upload(wo), b = test::upload(wi);
    Buffer out = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "eval");
    Kernel k = test::device().kernel(program, "probe_layered_eval");
    k.arg(0, mb).arg(1, layer_params(c.l)).arg(2, f4(c.l.coat_n)).arg(3, n).arg(4, a).arg(5, b).arg(6, out);
    test::run(k, n);
    return test::download<cl_float4>(out, n);
}

// ---- the reference, in double, frame-free (every cosine a dot product) ----

struct Ref {
    glm::dvec3 f;
    double pdf;
};
double schlick(double f0, double c) { return f0 + (1 - f0) * std::pow(std::clamp(1 - c, 0.0, 1.0), 5); }
double lum(glm::dvec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
double ggx_d(double cos_h, double a) {
    const double a2 = a * a;
    return a2 / (kPi * std::pow(cos_h * cos_h * (a2 - 1) + 1, 2));
}
double ggx_lambda(double c, double a) { return 0.5 * (std::sqrt(1 + a * a * (1 - c * c) / (c * c)) - 1); }

Ref reference(const Case& k, glm::dvec3 wo, glm::dvec3 wi) {
    if (wo.z <= 0 || wi.z == 0) return {glm::dvec3(0), 0};
    const Material& m = k.m;
    const double a = std::max(double(m.roughness) * m.roughness, 1e-3);
    const double ac = std::max(double(k.l.coat_roughness) * k.l.coat_roughness, 1e-3);
    const glm::dvec3 base(m.albedo[0], m.albedo[1], m.albedo[2]), nc = glm::normalize(glm::dvec3(k.l.coat_n));
    const double metal = m.metallic, f0 = std::pow((m.ior - 1.0) / (m.ior + 1.0), 2);
    const double c = k.l.clearcoat, t = k.l.transmission;
    const double co = glm::dot(wo, nc), ci = glm::dot(wi, nc);
    // Lobe probabilities at wo: albedo estimates.
    const double w_coat = co > 0 ? c * schlick(0.04, co) : 0, over = 1 - c * schlick(0.04, std::abs(co));
    const double fd = schlick(f0, wo.z);
    const glm::dvec3 fm0 = base + (glm::dvec3(1) - base) * std::pow(1 - wo.z, 5);
    const double w_spec = over * (metal * lum(fm0) + (1 - metal) * fd);
    const double w_body = over * (1 - metal) * (1 - fd) * lum(base);
    const double sum = w_coat + w_spec + w_body;
    double pc = 0, ps = 1, pd = 0, pt = 0;
    if (sum > 0) {
        pc = w_coat / sum;
        ps = w_spec / sum;
        pd = w_body * (1 - t) / sum;
        pt = w_body * t / sum;
    }
    const double under = over * (1 - c * schlick(0.04, std::abs(ci)));
    const double body = (1 - metal) * (1 - fd) * (1 - schlick(f0, std::abs(wi.z)));
    const double g1 = 1 / (1 + ggx_lambda(wo.z, a));
    if (wi.z < 0) {  // thin-walled transmission: the reflection lobe mirrored through the surface
        const glm::dvec3 wr(wi.x, wi.y, -wi.z), h = glm::normalize(wo + wr);
        const double d = ggx_d(h.z, a), g2 = 1 / (1 + ggx_lambda(wo.z, a) + ggx_lambda(wr.z, a));
        return {base * (under * body * t * d * g2 / (4 * wo.z)), pt * g1 * d / (4 * wo.z)};
    }
    const glm::dvec3 h = glm::normalize(wo + wi);
    const double d = ggx_d(h.z, a), g2 = 1 / (1 + ggx_lambda(wo.z, a) + ggx_lambda(wi.z, a));
    const double spec = d * g2 / (4 * wo.z), voh = glm::dot(wo, h);
    const glm::dvec3 fm = base + (glm::dvec3(1) - base) * std::pow(1 - voh, 5);
    glm::dvec3 f = under * (metal * fm * spec + glm::dvec3((1 - metal) * schlick(f0, voh) * spec) +
                            base * (body * (1 - t) / kPi * wi.z));
    double pdf = ps * g1 * d / (4 * wo.z) + pd * wi.z / kPi;
    if (c > 0 && co > 0 && ci > 0) {
        const double hn = glm::dot(h, nc), dc = ggx_d(hn, ac);
        const double g2c = 1 / (1 + ggx_lambda(co, ac) + ggx_lambda(ci, ac)), g1c = 1 / (1 + ggx_lambda(co, ac));
        f += glm::dvec3(c * schlick(0.04, voh) * dc * g2c / (4 * co * ci) * wi.z);
        pdf += pc * g1c * dc / (4 * co);
    }
    return {f, pdf};
}

Case gltf_case(glm::vec3 base, float metallic, float roughness, Layers l) {
    return {gltf_material(base, metallic, roughness), l};
}

const glm::vec3 kTilted = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));

const std::vector<Case>& configurations() {
    static const std::vector<Case> c = {
        gltf_case({0.8f, 0.2f, 0.1f}, 0.0f, 0.6f, {1.0f, 0.2f, 0.0f}),             // glossy coat on rough red plastic
        gltf_case({0.2f, 0.5f, 0.8f}, 0.0f, 0.3f, {0.6f, 0.5f, 0.0f, kTilted}),    // rough coat, own normal
        gltf_case({0.9f, 0.7f, 0.3f}, 1.0f, 0.5f, {1.0f, 0.2f, 0.0f}),             // coated metal
        gltf_case({0.9f, 0.9f, 0.9f}, 0.0f, 0.2f, {0.0f, 0.0f, 1.0f}),             // thin glass
        gltf_case({0.3f, 0.8f, 0.4f}, 0.0f, 0.7f, {0.0f, 0.0f, 0.5f}),             // half-transmitting rough
        gltf_case({0.8f, 0.6f, 0.9f}, 0.4f, 0.4f, {0.7f, 0.3f, 0.8f, kTilted}),    // all of it
    };
    return c;
}

glm::dvec3 random_sphere(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    const double z = 2 * u(rng) - 1, phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
}
glm::dvec3 random_upper(std::mt19937& rng) {
    glm::dvec3 d = random_sphere(rng);
    d.z = std::abs(d.z);
    return d;
}

std::string describe(const Case& c) {
    std::ostringstream o;
    o << "metallic " << c.m.metallic << " roughness " << c.m.roughness << " clearcoat " << c.l.clearcoat << " coat roughness "
      << c.l.coat_roughness << " transmission " << c.l.transmission << " coat normal " << c.l.coat_n.x << ","
      << c.l.coat_n.y << "," << c.l.coat_n.z;
    return o.str();
}

}  // namespace

// Against the double-precision reference, value and pdf, over the whole sphere
// of wi; with a near-mirror coat too (too sharp for the chi-square's grid).
TEST(GltfLayers, AgreesWithDoublePrecisionReference) {
    std::mt19937 rng(5);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 4000; ++i) {
        a.push_back(f4(glm::vec3(random_upper(rng))));
        b.push_back(f4(glm::vec3(random_sphere(rng))));
    }
    std::vector<Case> cases = configurations();
    cases.push_back(gltf_case({0.8f, 0.2f, 0.1f}, 0.0f, 0.6f, {1.0f, 0.05f, 0.0f}));
    cases.push_back(gltf_case({0.8f, 0.2f, 0.1f}, 0.0f, 0.05f, {0.0f, 0.0f, 1.0f}));
    for (const Case& c : cases) {
        SCOPED_TRACE(describe(c));
        const auto e = layered_eval(c, a, b);
        int nonzero = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const glm::dvec3 wo(a[i].s[0], a[i].s[1], a[i].s[2]), wi(b[i].s[0], b[i].s[1], b[i].s[2]);
            const Ref r = reference(c, wo, wi);
            // As for the core material, 1e-4 relative covers gamma(~800) over the
            // ~100 float operations. GGX's D is worse conditioned near its peak:
            // D = a^2 / (pi d^2) with d = a^2 + (1 - a^2) sin^2(theta_h), and
            // sin^2(theta_h), from a normalised sum of directions (and for the coat
            // a change of frame), carries an absolute error of some 16 ulps of 1:
            // relative 2 * 16 * 2^-24 / d in D, for the sharper of the lobes.
            const glm::dvec3 h = glm::normalize(wo + glm::dvec3(wi.x, wi.y, std::abs(wi.z)));
            double d_min = 1;
            for (double r : {double(c.m.roughness), double(c.l.coat_roughness)}) {
                const double al = std::max(r * r, 1e-3), s2 = std::max(0.0, 1 - h.z * h.z);
                d_min = std::min(d_min, al * al + (1 - al * al) * s2);
            }
            const double rel = 1e-4 + 2 * 16 * 0x1.0p-24 / d_min;
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[i].s[k], r.f[k], rel * std::abs(r.f[k]) + 1e-7) << i;
            EXPECT_NEAR(e[i].s[3], r.pdf, rel * r.pdf + 1e-7) << i;
            nonzero += r.f.y > 0 && b[i].s[2] < 0;
        }
        if (c.l.transmission > 0) {
            EXPECT_GT(nonzero, 1000) << "transmitted directions must be tested";
        }
    }
}

// The coat as the glTF specification defines it, where that has a closed
// form: a smooth coat of weight 1 reflects F(wo.n) of a white furnace, over
// which the base (black metal here) adds at most (1 - F(wo.n)) of its own
// albedo A0. So F <= A1 <= F + (1 - F) A0, to 6 standard errors (one-sided
// each, 3 angles x 2 bounds: below 1e-6 together) and the coat's near-mirror
// G2 / G1 (at least 0.999 at alpha 1e-3 up to 75 degrees).
TEST(GltfLayers, SmoothCoatReflectsFresnel) {
    const Case bare = gltf_case(glm::vec3(0), 1.0f, 1.0f, {0.0f, 0.0f, 0.0f});
    const Case coated = gltf_case(glm::vec3(0), 1.0f, 1.0f, {1.0f, 0.0f, 0.0f});
    auto albedo = [](const Case& c, double theta) {
        const Samples s = layered_sample(c, from_angle(theta), 100000, 13);
        std::vector<double> w;
        for (std::size_t i = 0; i < s.weight.size(); ++i) w.push_back(s.wi_pdf[i].s[3] > 0 ? s.weight[i].s[1] : 0.0);
        return test::mean_error(w);
    };
    for (double theta : {0.0, 45.0, 75.0}) {
        const double f = schlick(0.04, std::cos(theta * kPi / 180));
        const auto a0 = albedo(bare, theta), a1 = albedo(coated, theta);
        const double se = std::hypot(a0.std_error, a1.std_error);
        EXPECT_GT(a1.mean, 0.999 * f - 6 * a1.std_error) << theta;
        EXPECT_LT(a1.mean, f + (1 - f) * a0.mean + 6 * se) << theta;
        EXPECT_GT(a0.mean, 0.0) << "the bound must not be trivial";
    }
}

// 6 configurations x 2 angles share alpha = 1e-6 (Sidak).
const double kAlpha = 1 - std::pow(1 - 1e-6, 1.0 / 12);

TEST(GltfLayers, SamplingMatchesPdf) {
    for (const Case& c : configurations())
        for (double theta : {10.0, 70.0}) {
            SCOPED_TRACE(describe(c));
            const test::ChiSquare x = chi_square_by(
                [&](glm::vec3 wo, std::uint32_t n) { return layered_sample(c, wo, n); },
                [&](const std::vector<cl_float4>& wos, const std::vector<cl_float4>& wis) { return layered_eval(c, wos, wis); },
                theta, true);
            EXPECT_GT(x.p_value, kAlpha) << "chi2 " << x.statistic << " dof " << x.dof << " at theta " << theta;
        }
}

// Controls: the same test rejects sampling checked against a slightly wrong
// pdf: the coat's roughness off by 20%, and the transmitted share off by 20%.
TEST(GltfLayers, ChiSquareRejectsAWrongPdf) {
    auto p_of = [](const Case& drawn, const Case& checked, double theta) {
        return chi_square_by(
                   [&](glm::vec3 wo, std::uint32_t n) { return layered_sample(drawn, wo, n); },
                   [&](const std::vector<cl_float4>& wos, const std::vector<cl_float4>& wis) {
                       return layered_eval(checked, wos, wis);
                   },
                   theta, true)
            .p_value;
    };
    const Case coat = gltf_case({0.2f, 0.2f, 0.2f}, 0.0f, 0.6f, {1.0f, 0.3f, 0.0f});
    Case coat_wrong = coat;
    coat_wrong.l.coat_roughness = 0.36f;
    EXPECT_LT(p_of(coat, coat_wrong, 30), kAlpha);
    const Case glass = gltf_case({0.9f, 0.9f, 0.9f}, 0.0f, 0.3f, {0.0f, 0.0f, 1.0f});
    Case glass_wrong = glass;
    glass_wrong.l.transmission = 0.8f;
    EXPECT_LT(p_of(glass, glass_wrong, 30), kAlpha);
}

TEST(GltfLayers, SampleWeightEqualsEvalOverPdf) {
    for (const Case& c : configurations())
        for (double theta : {0.0, 40.0, 85.0}) {
            SCOPED_TRACE(describe(c));
            expect_weight_is_eval_over_pdf_by(
                [&](glm::vec3 wo, std::uint32_t n) { return layered_sample(c, wo, n); },
                [&](const std::vector<cl_float4>& wos, const std::vector<cl_float4>& wis) { return layered_eval(c, wos, wis); },
                from_angle(theta));
        }
}

// f(wo, wi) = f(wi, wo), transmission included (wo and wi on either side):
// eval returns f |cos theta_i|, so compare f = eval / |cos|. The coat normal
// is the shading normal here (a tilted one is not mirrored with the frame).
TEST(GltfLayers, Reciprocity) {
    std::mt19937 rng(3);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        a.push_back(f4(glm::vec3(random_upper(rng))));
        b.push_back(f4(glm::vec3(random_sphere(rng))));
    }
    for (const Case& c : configurations()) {
        if (c.l.coat_n != glm::vec3(0, 0, 1)) continue;
        SCOPED_TRACE(describe(c));
        const auto ab = layered_eval(c, a, b), ba = layered_eval(c, b, a);
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                const double f1 = ab[i].s[k] / std::abs(b[i].s[2]), f2 = ba[i].s[k] / std::abs(a[i].s[2]);
                // ~100 float operations on each side: gamma(256) relative.
                EXPECT_NEAR(f1, f2, 2 * 256 * 0x1.0p-24 * std::max(std::abs(f1), std::abs(f2)) + 1e-6) << i;
            }
    }
}

// With no coat and no transmission the layered BSDF is the core material (the
// program without layers), to float rounding.
TEST(GltfLayers, ZeroLayersAreTheCoreMaterial) {
    std::mt19937 rng(9);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        a.push_back(f4(glm::vec3(random_upper(rng))));
        b.push_back(f4(glm::vec3(random_upper(rng))));
    }
    for (const Material& m : {gltf_material({0.8f, 0.6f, 0.4f}, 0.0f, 0.3f), gltf_material({0.9f, 0.7f, 0.3f}, 1.0f, 0.6f),
                              gltf_material({0.5f, 0.9f, 0.5f}, 0.5f, 0.4f)}) {
        const auto core = eval(m, a, b), layered = layered_eval({m, Layers{}}, a, b);
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int k = 0; k < 4; ++k)
                EXPECT_NEAR(layered[i].s[k], core[i].s[k], 1e-5 * std::abs(core[i].s[k]) + 1e-7) << i << " " << k;
    }
}

// A program with the coat but no transmission (CLP_HAS_TRANSMISSION compiled
// out) gives the coat exactly as the program with both.
TEST(GltfLayers, CoatWithoutTransmissionProgram) {
    std::mt19937 rng(11);
    std::vector<cl_float4> a, b;
    for (int i = 0; i < 2000; ++i) {
        a.push_back(f4(glm::vec3(random_upper(rng))));
        b.push_back(f4(glm::vec3(random_sphere(rng))));
    }
    for (const Case& c : configurations()) {
        if (c.l.transmission > 0) continue;
        const auto both = layered_eval(c, a, b), coat_only = layered_eval(c, a, b, layered_program(false));
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int k = 0; k < 4; ++k) EXPECT_EQ(both[i].s[k], coat_only[i].s[k]) << i << " " << k;
    }
}

// The directional albedo (mean sample weight, reflection and transmission) of
// a white surface is at most 1. One-sided test: 5 x 3 x 3 x 4 = 180 cases
// share 1e-6 (Sidak): z = 6.1 standard errors.
double albedo_excess(const Case& c, double theta, double scale, double* mean) {
    const Samples s = layered_sample(c, from_angle(theta), 100000, 11);
    std::vector<double> w;
    for (std::size_t i = 0; i < s.weight.size(); ++i)
        w.push_back(s.wi_pdf[i].s[3] > 0 ? scale * s.weight[i].s[1] : 0.0);
    const auto e = test::mean_error(w);
    *mean = e.mean;
    return (e.mean - 1) / std::max(e.std_error, 1e-12);
}
constexpr double kFurnaceZ = 6.1;

TEST(GltfLayers, WhiteFurnaceNeverCreatesEnergy) {
    const Layers layers[] = {{1.0f, 0.0f, 0.0f}, {1.0f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.1f, 1.0f},
                             {0.5f, 1.0f, 0.5f}};
    for (const Layers& l : layers)
        for (float metallic : {0.0f, 0.5f, 1.0f})
            for (float rough : {0.0f, 0.4f, 1.0f})
                for (double theta : {0.0, 45.0, 80.0, 89.0}) {
                    const Case c = gltf_case(glm::vec3(1), metallic, rough, l);
                    double mean;
                    const double z = albedo_excess(c, theta, 1.0, &mean);
                    EXPECT_LT(z, kFurnaceZ) << describe(c) << " theta " << theta << ": albedo " << mean;
                }
}

// Control: the same statistic flags a transmitting surface (albedo 0.96:
// 0.04 reflected, 0.96^2 through) that returned 5% more.
TEST(GltfLayers, WhiteFurnaceRejectsEnergyGain) {
    double mean;
    EXPECT_GT(albedo_excess(gltf_case(glm::vec3(1), 0.0f, 0.0f, {0.0f, 0.0f, 1.0f}), 0.0, 1.05, &mean), kFurnaceZ) << mean;
}
