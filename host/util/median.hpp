#pragma once
// The median of a few timings: what the benchmarks report where one slow
// launch or pass (another process taking a core for a moment) should not
// move the figure, as it moves a mean.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace clpath {

// Median of the values (the mean of the middle two for an even count); 0 for none.
inline double median_of(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace clpath
