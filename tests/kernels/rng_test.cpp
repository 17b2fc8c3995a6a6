// The random number generator (kernels/rng.cl), run on the device:
// uniform, and independent between neighbouring pixels, successive samples
// and successive draws. Every test is a hypothesis test at alpha = 1e-4.
#include <gtest/gtest.h>

#include <cmath>

#include "support/statistics.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

constexpr double kAlpha = 1e-4;

std::vector<float> stream_numbers(std::uint32_t streams, std::uint32_t n, std::uint32_t sample, std::uint32_t seed) {
    Kernel k = test::device().kernel(test::probe_program(), "probe_rng_stream");
    Buffer out = test::device().buffer(std::size_t(streams) * n * sizeof(float), CL_MEM_READ_WRITE, "rng out");
    k.arg(0, out).arg(1, streams).arg(2, n).arg(3, sample).arg(4, seed);
    test::run(k, streams);
    return test::download<float>(out, std::size_t(streams) * n);
}

// first[s * pixels + p]: first number of stream (pixel p, sample s).
std::vector<float> first_numbers(std::uint32_t pixels, std::uint32_t samples, std::uint32_t seed) {
    Kernel k = test::device().kernel(test::probe_program(), "probe_rng_first");
    Buffer out = test::device().buffer(std::size_t(pixels) * samples * sizeof(float), CL_MEM_READ_WRITE, "rng out");
    k.arg(0, out).arg(1, pixels).arg(2, samples).arg(3, seed);
    test::run(k, std::size_t(pixels) * samples);
    return test::download<float>(out, std::size_t(pixels) * samples);
}

// Chi-square test that pairs (a[i], b[i]) are uniform on the unit square,
// i.e. each uniform and the two independent.
test::ChiSquare pair_test(const std::vector<float>& a, const std::vector<float>& b, int bins) {
    std::vector<double> obs(bins * bins, 0.0);
    for (std::size_t i = 0; i < a.size(); ++i) {
        int x = std::min(bins - 1, int(a[i] * bins)), y = std::min(bins - 1, int(b[i] * bins));
        obs[y * bins + x] += 1;
    }
    std::vector<double> exp(bins * bins, double(a.size()) / (bins * bins));
    return test::chi_square(obs, exp);
}

}  // namespace

TEST(Rng, NumbersAreInUnitInterval) {
    for (float v : stream_numbers(1024, 64, 0, 7)) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LT(v, 1.0f);
    }
}

TEST(Rng, UniformChiSquare) {
    const auto v = stream_numbers(4096, 256, 3, 1);
    const int bins = 1000;
    std::vector<double> obs(bins, 0.0), exp(bins, double(v.size()) / bins);
    for (float x : v) obs[std::min(bins - 1, int(x * bins))] += 1;
    auto r = test::chi_square(obs, exp);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
}

TEST(Rng, SuccessiveDrawsAreIndependent) {
    const auto v = stream_numbers(8192, 64, 0, 2);
    std::vector<float> a, b;
    for (std::size_t s = 0; s < 8192; ++s)
        for (std::size_t j = 0; j + 1 < 64; j += 2) {
            a.push_back(v[s * 64 + j]);
            b.push_back(v[s * 64 + j + 1]);
        }
    auto r = pair_test(a, b, 32);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic;
}

TEST(Rng, NeighbouringPixelsAreIndependent) {
    const std::uint32_t pixels = 1 << 18;
    const auto v = first_numbers(pixels, 1, 5);
    std::vector<float> a, b;
    for (std::uint32_t p = 0; p + 1 < pixels; p += 2) {
        a.push_back(v[p]);
        b.push_back(v[p + 1]);
    }
    auto r = pair_test(a, b, 32);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic;
}

TEST(Rng, SuccessiveSamplesAreIndependent) {
    const std::uint32_t pixels = 4096, samples = 64;
    const auto v = first_numbers(pixels, samples, 9);
    std::vector<float> a, b;
    for (std::uint32_t s = 0; s + 1 < samples; s += 2)
        for (std::uint32_t p = 0; p < pixels; ++p) {
            a.push_back(v[s * pixels + p]);
            b.push_back(v[(s + 1) * pixels + p]);
        }
    auto r = pair_test(a, b, 32);
    EXPECT_GT(r.p_value, kAlpha) << "chi2 = " << r.statistic;
}

TEST(Rng, NeighbourCorrelationIsZero) {
    // Pearson correlation of independent uniforms is ~ N(0, 1/n).
    const std::uint32_t pixels = 1 << 18;
    const auto v = first_numbers(pixels, 2, 11);
    auto corr = [&](auto pick_a, auto pick_b, std::size_t n) {
        double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = pick_a(i), y = pick_b(i);
            sa += x;
            sb += y;
            sab += x * y;
            saa += x * x;
            sbb += y * y;
        }
        const double cov = sab / n - sa / n * sb / n;
        return cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
    };
    const std::size_t n = pixels - 1;
    const double bound = test::normal_quantile_two_sided(kAlpha) / std::sqrt(double(n));
    EXPECT_LT(std::fabs(corr([&](std::size_t i) { return v[i]; }, [&](std::size_t i) { return v[i + 1]; }, n)), bound)
        << "pixel p vs p + 1";
    EXPECT_LT(std::fabs(corr([&](std::size_t i) { return v[i]; }, [&](std::size_t i) { return v[pixels + i]; }, n)),
              bound)
        << "sample s vs s + 1";
}

TEST(Rng, SeedsGiveDifferentStreams) {
    const auto a = stream_numbers(256, 4, 0, 1), b = stream_numbers(256, 4, 0, 2);
    int same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
    // Equal 24-bit values happen by chance with probability 2^-24 each.
    EXPECT_LE(same, 1);
}
