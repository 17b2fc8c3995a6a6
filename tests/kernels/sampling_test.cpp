// Cosine-weighted hemisphere sampling (kernels/sampling.cl): the directions
// follow cos(theta)/pi, checked by a chi-square goodness-of-fit test. The
// upper-half-plane atan2 the solid angle of a light triangle is taken with,
// and the cos and sin of pi x every sampled angle is turned into.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "support/statistics.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {
constexpr double kAlpha = 1e-4;
constexpr double kPi = 3.14159265358979323846;

std::vector<float> run_cosine(std::uint32_t n, std::uint32_t seed) {
    Kernel k = test::device().kernel(test::probe_program(), "probe_cosine");
    Buffer out = test::device().buffer(std::size_t(n) * 3 * sizeof(float), CL_MEM_READ_WRITE, "dirs");
    k.arg(0, out).arg(1, n).arg(2, seed);
    test::run(k, n);
    return test::download<float>(out, std::size_t(n) * 3);
}
}  // namespace

TEST(CosineSampling, ChiSquareAgainstCosineOverPi) {
    const std::uint32_t n = 1 << 20;
    const auto d = run_cosine(n, 1);
    // Cells in (cos theta, phi). The probability of a cell follows from the pdf:
    // P(z0 < z < z1, phi0 < phi < phi1) = (z1^2 - z0^2) (phi1 - phi0) / (2 pi).
    const int nz = 16, nphi = 32;
    std::vector<double> obs(nz * nphi, 0.0), exp(nz * nphi);
    for (std::uint32_t i = 0; i < n; ++i) {
        const double x = d[3 * i], y = d[3 * i + 1], z = d[3 * i + 2];
        ASSERT_NEAR(x * x + y * y + z * z, 1.0, 1e-5);
        ASSERT_GE(z, 0.0);
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        const int iz = std::min(nz - 1, int(z * nz)), ip = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
        obs[iz * nphi + ip] += 1;
    }
    for (int iz = 0; iz < nz; ++iz)
        for (int ip = 0; ip < nphi; ++ip) {
            const double z0 = double(iz) / nz, z1 = double(iz + 1) / nz;
            exp[iz * nphi + ip] = n * (z1 * z1 - z0 * z0) / nphi;
        }
    auto r = test::chi_square(obs, exp);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
}

TEST(CosineSampling, AboutArbitraryNormals) {
    // Through the frame code: cos to the normal must follow 2 z dz, i.e. z^2 uniform,
    // for normals in every octant, and along the axes where frames are fragile.
    const std::uint32_t n = 1 << 18;
    std::vector<float> normals(std::size_t(n) * 3);
    const float axes[][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.577350f, -0.577350f, 0.577350f}};
    for (std::uint32_t i = 0; i < n; ++i) {
        const float* a = axes[i % 5];
        for (int c = 0; c < 3; ++c) normals[3 * i + c] = a[c];
    }
    Kernel k = test::device().kernel(test::probe_program(), "probe_cosine_about");
    Buffer nb = test::upload(normals);
    Buffer out = test::device().buffer(normals.size() * sizeof(float), CL_MEM_READ_WRITE, "dirs");
    k.arg(0, nb).arg(1, out).arg(2, n).arg(3, 3u);
    test::run(k, n);
    const auto d = test::download<float>(out, normals.size());
    const int bins = 50;
    std::vector<double> obs(bins, 0.0), exp(bins, double(n) / bins);
    for (std::uint32_t i = 0; i < n; ++i) {
        double c = 0, len = 0;
        for (int j = 0; j < 3; ++j) {
            c += double(d[3 * i + j]) * normals[3 * i + j];
            len += double(d[3 * i + j]) * d[3 * i + j];
        }
        ASSERT_NEAR(len, 1.0, 1e-5);
        ASSERT_GE(c, -1e-6);
        obs[std::min(bins - 1, int(c * c * bins))] += 1;
    }
    auto r = test::chi_square(obs, exp);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic;
}

namespace {
struct Atan2Results {
    std::vector<float> y, x, out, naive;
};

Atan2Results run_atan2_upper(std::vector<float> y, std::vector<float> x) {
    const auto n = static_cast<std::uint32_t>(y.size());
    Kernel k = test::device().kernel(test::probe_program(), "probe_atan2_upper");
    Buffer yb = test::upload(y), xb = test::upload(x);
    Buffer out = test::device().buffer(y.size() * sizeof(float), CL_MEM_READ_WRITE, "atan2");
    Buffer naive = test::device().buffer(y.size() * sizeof(float), CL_MEM_READ_WRITE, "atan");
    k.arg(0, yb).arg(1, xb).arg(2, out).arg(3, naive).arg(4, n);
    test::run(k, n);
    return {std::move(y), std::move(x), test::download<float>(out, n), test::download<float>(naive, n)};
}

// The largest error of got[i] relative to atan2(y[i], x[i]) in double.
double worst_relative_error(const Atan2Results& r, const std::vector<float>& got) {
    double worst = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        const double exact = std::atan2(double(r.y[i]), double(r.x[i]));
        const double err = std::fabs(double(got[i]) - exact) / exact;
        worst = std::isnan(err) ? std::numeric_limits<double>::infinity() : std::max(worst, err);
    }
    return worst;
}
}  // namespace

namespace {
struct CosSinPi {
    std::vector<float> x, cos, sin, unreduced_cos, unreduced_sin;
};

CosSinPi run_cos_sin_pi(std::vector<float> x) {
    const auto n = static_cast<std::uint32_t>(x.size());
    Kernel k = test::device().kernel(test::probe_program(), "probe_cos_sin_pi");
    Buffer xb = test::upload(x);
    Buffer out = test::device().buffer(x.size() * 2 * sizeof(float), CL_MEM_READ_WRITE, "cos sin");
    Buffer unreduced = test::device().buffer(x.size() * 2 * sizeof(float), CL_MEM_READ_WRITE, "unreduced");
    k.arg(0, xb).arg(1, out).arg(2, unreduced).arg(3, n);
    test::run(k, n);
    const auto o = test::download<float>(out, 2 * std::size_t(n)), q = test::download<float>(unreduced, 2 * std::size_t(n));
    CosSinPi r{std::move(x), {}, {}, {}, {}};
    for (std::uint32_t i = 0; i < n; ++i) {
        r.cos.push_back(o[2 * i]);
        r.sin.push_back(o[2 * i + 1]);
        r.unreduced_cos.push_back(q[2 * i]);
        r.unreduced_sin.push_back(q[2 * i + 1]);
    }
    return r;
}

// cos(pi x) and sin(pi x) in double, x reduced exactly by multiples of 2 first.
double cos_pi(double x) { return std::cos(kPi * (x - 2.0 * std::nearbyint(0.5 * x))); }
double sin_pi(double x) { return std::sin(kPi * (x - 2.0 * std::nearbyint(0.5 * x))); }

// The largest error of got relative to the exact values, in units of 2^-24;
// a value that should be exactly 0 (sin of an integer, cos of a half-integer)
// must be 0.
double worst_error_u(const std::vector<float>& x, const std::vector<float>& got, double (*exact)(double)) {
    double worst = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double e = exact(double(x[i]));
        const bool zero = 2.0 * double(x[i]) == std::nearbyint(2.0 * double(x[i])) && std::fabs(e) < 1e-12;
        const double err = zero ? (got[i] == 0.0f ? 0.0 : std::numeric_limits<double>::infinity())
                                : std::fabs(double(got[i]) - e) / std::fabs(e) / std::ldexp(1.0, -24);
        worst = std::isnan(err) ? std::numeric_limits<double>::infinity() : std::max(worst, err);
    }
    return worst;
}

// The bound, u = 2^-24, first order. x = k/2 + y is exact (Sterbenz) and the
// quarter turns only swap and negate, so each result is one of the two
// polynomials at |y| <= 1/4. cos: 1 + t Q(t), t = y^2: Horner's ten roundings,
// gamma(10) sum|b_i| t^i / cos(pi y) <= 10u 1.325 / 0.707 = 18.8u; t's own
// rounding, |t c'(t)| u / c <= 0.44u; the fit's error 0.21u (in exact
// arithmetic, over 4e6 points). sin: y P(t): eight roundings, gamma(8) 3.475
// / 2.828 = 9.9u; the product by y, u; t, 0.12u; the fit, 0.54u. 20u covers both.
constexpr double kCosSinPiBoundU = 20.0;
}  // namespace

TEST(CosSinPi, RelativeErrorWithinItsBoundInEveryQuarterTurn) {
    // A dense grid over [-2, 2] (every quarter turn, both signs), the points
    // where the turn changes (odd multiples of 1/4) with their neighbours,
    // tiny angles, and large ones, where k is even and y 0 or a multiple of 1/4.
    std::vector<float> x;
    for (int i = -(1 << 19); i <= (1 << 19); ++i) x.push_back(float(i) / float(1 << 17));
    for (int q = -9; q <= 9; q += 2)
        for (float v = float(q) * 0.25f, d = 0; d < 8; ++d) {
            x.push_back(v);
            v = std::nextafter(v, 10.0f);
        }
    for (float v : {1e-30f, -1e-20f, 3e-8f, 1e3f + 0.3f, -12345.678f, 4194304.5f, 16777216.0f, 1e30f}) x.push_back(v);
    const CosSinPi r = run_cos_sin_pi(x);
    const double wc = worst_error_u(r.x, r.cos, cos_pi), ws = worst_error_u(r.x, r.sin, sin_pi);
    EXPECT_LE(wc, kCosSinPiBoundU);
    EXPECT_LE(ws, kCosSinPiBoundU);
    std::printf("cos_sin_pi: worst relative error cos %.2f u, sin %.2f u, bound %.0f u\n", wc, ws, kCosSinPiBoundU);
}

TEST(CosSinPi, ControlTheUnreducedPolynomialsAreRejected) {
    // The same check rejects the quarter-interval polynomials applied beyond
    // the quarter, where they are no longer cos and sin.
    const CosSinPi r = run_cos_sin_pi({0.1f, 0.3f, 0.9f, -1.6f});
    EXPECT_LE(std::max(worst_error_u(r.x, r.cos, cos_pi), worst_error_u(r.x, r.sin, sin_pi)), kCosSinPiBoundU);
    EXPECT_GT(std::max(worst_error_u(r.x, r.unreduced_cos, cos_pi), worst_error_u(r.x, r.unreduced_sin, sin_pi)),
              1e3);
}

TEST(Atan2Upper, RelativeErrorWithinItsBoundInEveryOctant) {
    // y >= 0, x of either sign, both over 2^-20..2^20 so that every octant
    // of the upper half-plane and quotients from 2^-40 to 1 occur, and pairs
    // near the diagonal |x| = y, where the octant switches.
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> mant(1.0f, 2.0f), near(0.999f, 1.001f);
    std::uniform_int_distribution<int> expo(-20, 20);
    std::vector<float> y, x;
    for (int i = 0; i < 1 << 18; ++i) {
        const float a = std::ldexp(mant(gen), expo(gen)), b = std::ldexp(mant(gen), expo(gen));
        const float sign = (i & 1) ? -1.0f : 1.0f;
        y.push_back(a);
        x.push_back(sign * ((i & 2) ? b : a * near(gen)));
    }
    const Atan2Results r = run_atan2_upper(y, x);
    // The bound, u = 2^-24, first order: the quotient r = min/max, 2.5 ulp in
    // OpenCL (5u), carried at most 1:1 to atan(r) (r atan'(r)/atan(r) <= 1);
    // Horner with fused multiply-adds, gamma(8) sum|c_i| / P(1) <= 2.2 gamma(8)
    // (sum|c_i| = 1.72, P >= pi/4); s = r^2 rounded, |P'| s u / P <= 0.44u; the
    // product r P, u; pi/2 - a and pi - a, 3u each (a rounded pi, the
    // subtraction, the error of a over a result at least as large); the
    // Chebyshev fit's own 1.78e-8 over P >= pi/4. About 30u + 2.3e-8.
    const double u = std::ldexp(1.0, -24);
    const double bound = 32.0 * u + 2.3e-8;
    const double worst = worst_relative_error(r, r.out);
    EXPECT_LE(worst, bound);
    std::printf("atan2_upper: worst relative error %.3g (%.2f u), bound %.3g\n", worst, worst / u, bound);
}

TEST(Atan2Upper, ControlAtanOfTheQuotientIsRejected) {
    // The same check rejects atan(y/x), which is wrong for x < 0.
    const Atan2Results r = run_atan2_upper({1.0f, 0.5f, 3.0f, 2.0f}, {2.0f, -1.0f, 0.25f, -7.0f});
    EXPECT_LE(worst_relative_error(r, r.out), 32.0 * std::ldexp(1.0, -24) + 2.3e-8);
    EXPECT_GT(worst_relative_error(r, r.naive), 1.0);
}

TEST(Atan2Upper, AxesZerosAndNaN) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Atan2Results r = run_atan2_upper({0.0f, 0.0f, 2.0f, 0.0f, 0.0f, nan, 1.0f, 3.0f},
                                           {1.0f, -1.0f, 0.0f, 0.0f, -0.0f, 1.0f, nan, 3.0f});
    EXPECT_EQ(r.out[0], 0.0f);
    EXPECT_FLOAT_EQ(r.out[1], float(kPi));
    EXPECT_FLOAT_EQ(r.out[2], float(kPi / 2));
    EXPECT_EQ(r.out[3], 0.0f);  // atan2(0, 0): 0
    EXPECT_EQ(r.out[4], 0.0f);  // atan2(0, -0): 0 here, where C gives pi (sampling.cl)
    EXPECT_TRUE(std::isnan(r.out[5]));
    EXPECT_TRUE(std::isnan(r.out[6]));
    EXPECT_FLOAT_EQ(r.out[7], float(kPi / 4));
}
