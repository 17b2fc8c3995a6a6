#include "support/image_agreement.hpp"

#include <cmath>
#include <stdexcept>

#include "support/statistics.hpp"

namespace clpath::test {
namespace {
struct PixelStats {
    std::vector<double> mean, var_of_mean;  // per pixel and channel
};

PixelStats pixel_stats(const std::vector<Image>& runs) {
    if (runs.size() < 2) throw std::invalid_argument("image_agreement needs at least two runs per side");
    const std::size_t n = runs[0].rgb.size();
    const double k = double(runs.size());
    PixelStats s;
    s.mean.assign(n, 0.0);
    s.var_of_mean.assign(n, 0.0);
    for (const auto& r : runs) {
        if (r.rgb.size() != n) throw std::invalid_argument("image_agreement: sizes differ");
        for (std::size_t i = 0; i < n; ++i) s.mean[i] += r.rgb[i] / k;
    }
    for (const auto& r : runs)
        for (std::size_t i = 0; i < n; ++i) {
            const double d = r.rgb[i] - s.mean[i];
            s.var_of_mean[i] += d * d / ((k - 1) * k);
        }
    return s;
}
}  // namespace

Agreement image_agreement(const std::vector<Image>& a, const std::vector<Image>& b, int block, double alpha) {
    const PixelStats sa = pixel_stats(a), sb = pixel_stats(b);
    const int w = a[0].width, h = a[0].height;
    if (b[0].width != w || b[0].height != h) throw std::invalid_argument("image_agreement: sizes differ");
    Agreement r;
    const int bx = (w + block - 1) / block, by = (h + block - 1) / block;
    r.blocks = bx * by * 3;
    const double alpha_block = 1 - std::pow(1 - alpha, 1.0 / r.blocks);
    r.critical_z = normal_quantile_two_sided(alpha_block);
    for (int yb = 0; yb < by; ++yb)
        for (int xb = 0; xb < bx; ++xb)
            for (int c = 0; c < 3; ++c) {
                double diff = 0, var = 0;
                int count = 0;
                for (int y = yb * block; y < std::min(h, (yb + 1) * block); ++y)
                    for (int x = xb * block; x < std::min(w, (xb + 1) * block); ++x) {
                        const std::size_t i = (std::size_t(y) * w + x) * 3 + c;
                        diff += sa.mean[i] - sb.mean[i];
                        var += sa.var_of_mean[i] + sb.var_of_mean[i];
                        ++count;
                    }
                diff /= count;
                var /= double(count) * count;
                // A block that is exactly equal with zero variance agrees.
                const double z = var > 0 ? std::abs(diff) / std::sqrt(var) : (diff == 0 ? 0 : INFINITY);
                if (z > r.critical_z) ++r.failed;
                if (!(z <= r.worst_z)) {
                    r.worst_z = z;
                    r.worst_x = xb * block;
                    r.worst_y = yb * block;
                }
            }
    return r;
}

std::string Agreement::describe() const {
    return std::to_string(failed) + " of " + std::to_string(blocks) + " blocks differ (critical z " +
           std::to_string(critical_z) + ", worst z " + std::to_string(worst_z) + " at (" + std::to_string(worst_x) +
           ", " + std::to_string(worst_y) + "))";
}

}  // namespace clpath::test
