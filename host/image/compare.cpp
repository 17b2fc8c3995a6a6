#include "image/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "util/error.hpp"

namespace clpath {

ImageComparison compare_images(const Image& a, const Image& b, const CompareOptions& o) {
    if (a.width != b.width || a.height != b.height)
        throw Error("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                    std::to_string(b.width) + "x" + std::to_string(b.height));
    auto clamp = [&](float v) { return o.clamp > 0 ? std::clamp(v, 0.0f, o.clamp) : v; };
    ImageComparison c;
    // Sums in double: a 4K image has 2.5e7 terms.
    double se = 0, rel = 0;
    std::array<double, 3> sa{}, sb{};
    std::vector<char> masked(std::size_t(a.width) * a.height, 0);
    if (o.mask_above > 0)
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                if (!(std::max({b.at(x, y, 0), b.at(x, y, 1), b.at(x, y, 2)}) > o.mask_above)) continue;
                const int g = std::max(0, o.mask_grow);
                for (int j = std::max(0, y - g); j <= std::min(a.height - 1, y + g); ++j)
                    for (int i = std::max(0, x - g); i <= std::min(a.width - 1, x + g); ++i)
                        masked[std::size_t(j) * a.width + i] = 1;
            }
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (masked[std::size_t(y) * a.width + x]) continue;
            ++c.pixels;
            for (int ch = 0; ch < 3; ++ch) {
                const double va = clamp(a.at(x, y, ch)), vb = clamp(b.at(x, y, ch));
                const double d = va - vb;
                se += d * d;
                rel += d * d / (vb * vb + 1e-2);
                sa[ch] += va;
                sb[ch] += vb;
                // A NaN difference is the largest of all, and stays reported.
                if (!std::isnan(c.max_abs_diff) && !(std::abs(d) <= c.max_abs_diff)) {
                    c.max_abs_diff = std::abs(d);
                    c.max_x = x;
                    c.max_y = y;
                }
            }
        }
    if (c.pixels == 0) throw Error("no pixels left to compare after masking");
    const double n = double(c.pixels) * 3;
    c.mse = se / n;
    c.rmse = std::sqrt(c.mse);
    c.relmse = rel / n;
    c.psnr = c.mse > 0 ? 10.0 * std::log10(1.0 / c.mse) : std::numeric_limits<double>::infinity();
    for (int ch = 0; ch < 3; ++ch) {
        c.mean_a[ch] = sa[ch] / double(c.pixels);
        c.mean_b[ch] = sb[ch] / double(c.pixels);
    }
    return c;
}

std::string describe(const ImageComparison& c) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "rmse=%.6g psnr=%.3f mse=%.6g relmse=%.6g mean_a=(%.6g,%.6g,%.6g) mean_b=(%.6g,%.6g,%.6g) "
                  "max_diff=%.6g at (%d,%d) pixels=%zu",
                  c.rmse, c.psnr, c.mse, c.relmse, c.mean_a[0], c.mean_a[1], c.mean_a[2], c.mean_b[0], c.mean_b[1],
                  c.mean_b[2], c.max_abs_diff, c.max_x, c.max_y, c.pixels);
    return buf;
}

}  // namespace clpath
