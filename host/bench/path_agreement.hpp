#pragma once
// Whether two renders of the same scene compute the same estimator: clpath's
// image (per-pixel means of n_a samples) against a CPU tracer's per-pixel
// sums and sums of squares (n_b samples, independent random streams). Under
// that hypothesis both draw every pixel's samples from one distribution, so
// the CPU tracer's per-pixel sample variance is the variance of both, and the
// difference of two means over a set of pixels has the variance
// sum_p s_p^2 (1/n_a + 1/n_b) / |set|^2. The z-scores of the whole image's
// mean (per channel) and of a grid of regions' means (per channel) are
// compared against one bound, Bonferroni-corrected so that a correct pair of
// renders fails with probability below 1e-6 (normal approximation of means
// over thousands of samples).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/embree_path_tracer.hpp"
#include "image/image.hpp"

namespace clpath {

struct PathAgreement {
    std::array<double, 3> mean_a{}, mean_b{}, z{};  // the whole image, per channel
    int grid = 0;                                   // regions per side
    double max_region_z = 0;                        // largest |z| over the regions and channels
    int worst_region = -1, worst_channel = -1;      // where (region = row * grid + column)
    double bound = 0;                               // |z| above it fails
    double false_failure = 1e-6;                    // the chance that a correct pair fails, bound chosen for it
    int tests = 0;                                  // z-scores compared against the bound
    bool agrees() const;
    // "R 0.1234 / 0.1236 (z -0.51), G ..., B ...; 16 regions x 3 channels, max |z| 2.90; bound 5.73 (...)"
    std::string describe() const;
};

// The bound on |z| that m two-sided tests exceed together with probability at
// most alpha under the null hypothesis (Bonferroni): P(|Z| > bound) = alpha / m.
double bonferroni_z_bound(double alpha, int m);

// a: clpath's mean image; b: the CPU tracer's sums (same size, n_b >= 2).
// grid x grid regions (grid >= 1, at most the image's smaller side). Throws
// clpath::Error for mismatched sizes or too few samples.
PathAgreement check_path_agreement(const Image& a, std::uint64_t n_a, const PathSums& b, int grid = 4,
                                   double false_failure = 1e-6);

}  // namespace clpath
