// Cosine-weighted hemisphere sampling (kernels/sampling.cl): the directions
// follow cos(theta)/pi, checked by a chi-square goodness-of-fit test.
#include <gtest/gtest.h>

#include <cmath>

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
