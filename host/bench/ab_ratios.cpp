#include "bench/ab_ratios.hpp"

#include <algorithm>
#include <cstdio>

namespace clpath {

void finish_ab(AbResult& ab) {
    std::vector<double> r = ab.ratios;
    std::sort(r.begin(), r.end());
    auto at = [&](double q) {
        const double x = q * double(r.size() - 1);
        const auto i = std::size_t(x);
        return i + 1 < r.size() ? r[i] + (x - double(i)) * (r[i + 1] - r[i]) : r[i];
    };
    ab.median = at(0.5);
    ab.q1 = at(0.25);
    ab.q3 = at(0.75);
    ab.ran = true;
}

std::string describe_ab_ratios(const AbResult& ab) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "variant/built-in %.3f (quartiles %.3f-%.3f) over %zu launch pairs", ab.median,
                  ab.q1, ab.q3, ab.ratios.size());
    return buf;
}

}  // namespace clpath
