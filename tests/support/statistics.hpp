#pragma once
// Statistics the accuracy tests share: tolerances come from these, never
// from numbers tuned until green.
#include <cstddef>
#include <vector>

namespace clpath::test {

// Upper tail probability of the chi-square distribution with k degrees of freedom.
double chi_square_sf(double x, double k);

// Pearson's chi-square statistic and its p-value for observed counts against
// expected counts; cells with expected count below 5 are pooled first (the
// usual validity condition).
struct ChiSquare {
    double statistic = 0, p_value = 0;
    int dof = 0;
};
ChiSquare chi_square(const std::vector<double>& observed, const std::vector<double>& expected);

// Mean and the standard error of the mean of independent samples.
struct MeanError {
    double mean = 0, std_error = 0, variance = 0;
};
MeanError mean_error(const std::vector<double>& x);

// Two-sided normal critical value for significance alpha (e.g. 1e-4 -> 3.89).
double normal_quantile_two_sided(double alpha);

// Two-sided tail probability P(|T| >= t) of Student's t distribution with dof
// degrees of freedom (dof may be fractional, as Welch's is; infinity: normal).
double student_t_two_sided_p(double t, double dof);

}  // namespace clpath::test
