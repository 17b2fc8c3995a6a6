#include "support/statistics.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace clpath::test {
namespace {

// Regularized upper incomplete gamma Q(a, x), Numerical Recipes' series and
// continued fraction (Press et al., 3rd ed., 6.2).
double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double lg = std::lgamma(a);
    if (x < a + 1) {
        double sum = 1.0 / a, term = sum;
        for (int n = 1; n < 10000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - lg);
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::fabs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lg) * h;
}

// Regularized incomplete beta I_x(a, b) by Lentz's continued fraction
// (Press et al., 3rd ed., 6.4), using the symmetry for x above the mean.
double beta_cf(double a, double b, double x) {
    const double tiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    if (std::fabs(d) < tiny) d = tiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m < 10000; ++m) {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a - 1 + m2) * (a + m2));
        d = 1 + aa * d;
        if (std::fabs(d) < tiny) d = tiny;
        c = 1 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1 + m2));
        d = 1 + aa * d;
        if (std::fabs(d) < tiny) d = tiny;
        c = 1 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-15) break;
    }
    return h;
}

double incomplete_beta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    const double front =
        std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
    if (x < (a + 1) / (a + b + 2)) return front * beta_cf(a, b, x) / a;
    return 1 - front * beta_cf(b, a, 1 - x) / b;
}

}  // namespace

double student_t_two_sided_p(double t, double dof) {
    t = std::fabs(t);
    if (!(dof < 1e7)) return std::erfc(t / std::sqrt(2.0));
    return incomplete_beta(dof / 2, 0.5, dof / (dof + t * t));
}

double chi_square_sf(double x, double k) { return gamma_q(k / 2, x / 2); }

ChiSquare chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    if (observed.size() != expected.size()) throw std::invalid_argument("chi_square: size mismatch");
    ChiSquare r;
    double pooled_o = 0, pooled_e = 0;
    int cells = 0;
    auto add = [&](double o, double e) {
        r.statistic += (o - e) * (o - e) / e;
        ++cells;
    };
    for (std::size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5) {
            pooled_o += observed[i];
            pooled_e += expected[i];
            if (pooled_e >= 5) {
                add(pooled_o, pooled_e);
                pooled_o = pooled_e = 0;
            }
        } else {
            add(observed[i], expected[i]);
        }
    }
    if (pooled_e > 0) add(pooled_o, pooled_e);
    r.dof = cells - 1;
    r.p_value = chi_square_sf(r.statistic, r.dof);
    return r;
}

MeanError mean_error(const std::vector<double>& x) {
    MeanError m;
    const double n = double(x.size());
    m.mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
    double ss = 0;
    for (double v : x) ss += (v - m.mean) * (v - m.mean);
    m.variance = ss / (n - 1);
    m.std_error = std::sqrt(m.variance / n);
    return m;
}

double normal_quantile_two_sided(double alpha) {
    // Bisection on erfc: erfc(z / sqrt 2) = alpha.
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace clpath::test
