// Triangle-light sampling of kernels/lights.cl, run on the test device: the
// points it samples follow its own pdf (chi-square), that pdf is the solid
// angle's inverse where solid-angle sampling (Arvo 1995) applies and the area
// pdf elsewhere, and the pdf MIS evaluates for a sampled direction is the one
// the sample carried.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "shared_structs.h"
#include "support/statistics.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

using dvec3 = glm::dvec3;

// The light: a right triangle in the z = 0 plane, emitting towards +z.
const dvec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

Light triangle_light() {
    Light l{};
    for (int i = 0; i < 3; ++i) {
        l.a[i] = float(kA[i]);
        l.b[i] = float(kB[i]);
        l.c[i] = float(kC[i]);
        l.L[i] = 1.0f;
    }
    l.type = CLP_LIGHT_TRIANGLE;
    return l;
}

// Solid angle of the triangle seen from p, in double (Van Oosterom & Strackee).
double solid_angle(dvec3 p) {
    const dvec3 a = glm::normalize(kA - p), b = glm::normalize(kB - p), c = glm::normalize(kC - p);
    return 2 * std::atan2(std::abs(glm::dot(a, glm::cross(b, c))), 1 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
}

// The kernel's rule: solid-angle sampling for a triangle not small for its
// distance, between these solid angles, for points at least a tenth of the
// nearest vertex's distance off the plane.
bool sampled_by_solid_angle(dvec3 p) {
    const double omega = solid_angle(p);
    const double nearest = std::min({glm::length(kA - p), glm::length(kB - p), glm::length(kC - p)});
    const double area = 0.5 * glm::length(glm::cross(kB - kA, kC - kA));
    return area >= CLP_MIN_SPHERICAL_SPREAD * nearest * nearest && omega >= CLP_MIN_SPHERICAL_AREA &&
           omega <= CLP_MAX_SPHERICAL_AREA && std::abs(p.z) >= CLP_MIN_SPHERICAL_ELEVATION * nearest;
}

// The point of the triangle at square-root-warp coordinates (u1, u2), the
// parametrisation in which area sampling is uniform: dA = area du1 du2.
dvec3 point_at(double u1, double u2) {
    const double su = std::sqrt(u1), b0 = 1 - su, b1 = u2 * su;
    return b0 * kA + b1 * kB + (1 - b0 - b1) * kC;
}

// Density in (u1, u2) of the kernel's sampling from p.
double density(dvec3 p, double u1, double u2) {
    if (!sampled_by_solid_angle(p)) return 1.0;
    const dvec3 q = point_at(u1, u2), d = q - p;
    const double r2 = glm::dot(d, d), cos_l = std::abs(d.z) / std::sqrt(r2);
    return 0.5 * cos_l / (r2 * solid_angle(p));  // (1 / omega) d(omega) = (1 / omega) cos / r^2 dA, dA = 0.5 du1 du2
}

struct Samples {
    std::vector<cl_float4> q_pdf;
    std::vector<float> mis_pdf;
};

Samples sample(dvec3 p, std::uint32_t n) {
    Buffer lb = test::upload(std::vector<Light>{triangle_light()}, "light");
    Buffer out = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "samples");
    Buffer pdf = test::device().buffer(n * sizeof(float), CL_MEM_READ_WRITE, "pdfs");
    Kernel k = test::device().kernel(test::probe_program(), "probe_triangle_light");
    k.arg(0, lb).arg(1, float(p.x)).arg(2, float(p.y)).arg(3, float(p.z)).arg(4, n).arg(5, std::uint32_t(11));
    k.arg(6, out).arg(7, pdf);
    test::run(k, n);
    return {test::download<cl_float4>(out, n), test::download<float>(pdf, n)};
}

// Points seen from these places, from beside the light to far away.
// Grazing places are on both sides of the elevation rule (height over the
// plane / nearest vertex distance: 0.12 and 0.118 are sampled by solid angle,
// 0.008 and 0.026 by area, where the spherical construction fails in float).
const dvec3 kPlaces[] = {
    {0.3, 0.3, 0.05},     // just in front: nearly a hemisphere of light
    {0.2, 0.5, 1.0},      // an ordinary distance
    {0.3, 0.3, 100.0},    // far away: area sampling
    {0.3, 0.3, 2.5},      // small for its distance (area 0.5 < 0.1 x 6.43): area sampling
    {1.2, 1.2, 0.146},    // low over the plane, beside the light: solid angle
    {-0.14, -0.84, 0.1},  // low, beside a vertex: solid angle
    {1.2, 1.2, 0.01},     // grazing (a wall just below a ceiling lamp): area
    {-0.14, -0.84, 0.022},
};
constexpr int kPlaceCount = 8;

// Chi-square of the sampled points, binned on a 20 x 20 grid in (u1, u2),
// against the density integrated over each cell by the midpoint rule on an
// 8 x 8 sub-grid. The places share alpha = 1e-3 (Sidak).
TEST(Lights, TriangleSamplingMatchesItsPdf) {
    const double alpha = 1 - std::pow(1 - 1e-3, 1.0 / kPlaceCount);
    const int cells = 20, sub = 8;
    const std::uint32_t n = 200000;
    for (const dvec3& p : kPlaces) {
        const Samples s = sample(p, n);
        std::vector<double> observed(cells * cells, 0.0), expected(cells * cells, 0.0);
        int failed = 0;
        for (const auto& v : s.q_pdf) {
            if (v.s[3] < 0) {
                ++failed;
                continue;
            }
            // Barycentrics of the sample (it lies a rounding error off the plane).
            const dvec3 q(v.s[0], v.s[1], 0.0);
            const double b1 = q.x, b2 = q.y, su = std::clamp(b1 + b2, 0.0, 1.0);
            const double u1 = su * su, u2 = su > 0 ? b1 / su : 0.0;
            const int i = std::min(cells - 1, int(u1 * cells)), j = std::min(cells - 1, int(u2 * cells));
            observed[i * cells + j] += 1;
        }
        EXPECT_EQ(failed, 0) << "samples lost from p = (" << p.x << ", " << p.y << ", " << p.z << ")";
        const double h = 1.0 / (cells * sub);
        for (int i = 0; i < cells * sub; ++i)
            for (int j = 0; j < cells * sub; ++j)
                expected[(i / sub) * cells + j / sub] += density(p, (i + 0.5) * h, (j + 0.5) * h) * h * h * n;
        const test::ChiSquare c = test::chi_square(observed, expected);
        EXPECT_GT(c.p_value, alpha) << "chi2 " << c.statistic << " dof " << c.dof << " from p = (" << p.x << ", "
                                    << p.y << ", " << p.z << ")";
    }
}

// The pdf a sample carries is the inverse solid angle (or the area pdf), and
// MIS evaluates the same pdf for the same direction. Tolerance: the float
// solid angle is a few dozen roundings (relative 2^-24 each) away from the
// double one, amplified by at most the conditioning of these well-separated
// vertices: 1e-4 relative is two orders above that.
TEST(Lights, TriangleSamplePdfIsConsistent) {
    for (const dvec3& p : kPlaces) {
        const Samples s = sample(p, 4096);
        const bool by_angle = sampled_by_solid_angle(p);
        for (std::size_t i = 0; i < s.q_pdf.size(); ++i) {
            const auto& v = s.q_pdf[i];
            ASSERT_GT(v.s[3], 0.0f);
            double expected;
            if (by_angle) {
                expected = 1 / solid_angle(p);
            } else {
                const dvec3 d = dvec3(v.s[0], v.s[1], v.s[2]) - p;
                const double r2 = glm::dot(d, d);
                expected = r2 / (0.5 * std::abs(d.z) / std::sqrt(r2));
            }
            ASSERT_NEAR(v.s[3], expected, 1e-4 * expected) << "sample " << i << " from z = " << p.z;
            ASSERT_NEAR(s.mis_pdf[i], v.s[3], 1e-4 * v.s[3]) << "sample " << i << " from z = " << p.z;
        }
    }
}

// Behind a one-sided light nothing is sampled; beside it in its plane, nothing
// non-finite comes out.
TEST(Lights, TriangleSamplingBehindAndInPlane) {
    for (const dvec3& p : {dvec3(0.3, 0.3, -0.5), dvec3(2.0, 0.5, 0.0), dvec3(0.25, 0.25, 0.0)}) {
        const Samples s = sample(p, 4096);
        for (const auto& v : s.q_pdf) {
            ASSERT_TRUE(std::isfinite(v.s[0]) && std::isfinite(v.s[1]) && std::isfinite(v.s[2]) &&
                        std::isfinite(v.s[3]));
            ASSERT_EQ(v.s[3], -1.0f) << "a sample from p = (" << p.x << ", " << p.y << ", " << p.z << ")";
        }
    }
}

}  // namespace
