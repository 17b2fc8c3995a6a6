#pragma once
// Are two renderers' images equal in distribution? Each side is rendered K
// times with independent seeds; per pixel, the runs give a mean and the
// variance of that mean. Pixels are pooled into blocks, and each block's
// difference is z-tested against its standard error. The significance is
// Sidak-corrected over blocks, so an agreeing pair fails with probability
// alpha in all (after Mitsuba 3's render tests, on blocks rather than pixels
// so that the normal approximation holds at small sample counts).
#include <cmath>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace clpath::test {

struct Agreement {
    int blocks = 0, failed = 0;
    double worst_z = 0;       // largest |z| over blocks
    int worst_x = 0, worst_y = 0;
    double critical_z = 0;    // the Sidak-corrected threshold
    bool ok() const { return failed == 0; }
    std::string describe() const;
};

Agreement image_agreement(const std::vector<Image>& a, const std::vector<Image>& b, int block = 8,
                          double alpha = 0.01);

// ---- per-pixel test against a reference (Mitsuba 3's render tests) ---------
// A reference: per pixel and channel, the expected value and the variance of
// that estimate, with the degrees of freedom of the variance estimate
// (infinity when it is known: an analytic image has variance 0; a reference
// rendered with N samples and a per-sample variance image has var/N).
struct Reference {
    std::string name;
    Image mean;
    std::vector<double> var_of_mean;  // empty: exact (analytic)
    double dof = INFINITY;
    // Where the variance of clpath's own estimate is known in closed form
    // (0/1 samples of expectation m: m (1 - m) / samples), it replaces the
    // runs' spread, which is 0 where every run happened to give the same value.
    std::vector<double> run_var_of_mean;
};
// The mean of K independent runs, with the variance of that mean from their spread (dof K - 1).
Reference reference_from_runs(const std::string& name, const std::vector<Image>& runs);
// An analytic image: no variance.
Reference reference_exact(const std::string& name, const Image& image);
// A reference image whose variance is not stored, only its sample count N: its
// per-sample variance is taken to be clpath's own (estimated from the runs it
// is compared with, rendered at spp_per_run each), so var_of_mean = s^2 / N.
// An approximation for a reference from another renderer (another estimator
// has another variance); exact in kind for a clpath reference.
Reference reference_from_sample_count(const std::string& name, const Image& image, double samples,
                                      const std::vector<Image>& runs, double spp_per_run);

struct PixelAgreement {
    std::string reference;
    int values = 0, failed = 0;  // pixel channels tested, and those that failed
    double alpha_value = 0;      // the Sidak-corrected significance of one value
    double worst_p = 1;
    int worst_x = 0, worst_y = 0, worst_c = 0;
    double required = 0.9975;
    double pass_fraction() const { return values ? 1.0 - double(failed) / values : 0.0; }
    bool ok() const { return values > 0 && pass_fraction() >= required; }
    std::string describe() const;
};
// Every pixel channel of the runs' mean is t-tested against the reference
// (Welch's test: the variance of the difference is the sum of both sides',
// with Welch-Satterthwaite degrees of freedom), at the Sidak-corrected level
// 1 - (1 - alpha)^(1/values); the images agree when at least `required` of
// the values pass. A value whose difference has zero variance passes when the
// difference is within rounding_rel of the reference (a float error bound the
// caller states).
PixelAgreement pixel_agreement(const std::vector<Image>& runs, const Reference& ref, double alpha = 0.01,
                               double required = 0.9975, double rounding_rel = 0);

}  // namespace clpath::test
