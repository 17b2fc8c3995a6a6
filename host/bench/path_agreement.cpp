#include "bench/path_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util/error.hpp"

namespace clpath {

double bonferroni_z_bound(double alpha, int m) {
    const double target = alpha / double(std::max(1, m));
    // P(|Z| > t) = erfc(t / sqrt 2) falls monotonically: bisection.
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > target ? lo : hi) = mid;
    }
    return hi;
}

bool PathAgreement::agrees() const {
    for (double v : z)
        if (!(std::fabs(v) <= bound)) return false;
    return max_region_z <= bound;
}

std::string PathAgreement::describe() const {
    static const char* names = "RGB";
    std::string s;
    char buf[200];
    for (int c = 0; c < 3; ++c) {
        std::snprintf(buf, sizeof buf, "%s%c %.6g / %.6g (z %+.2f)", c ? ", " : "", names[c], mean_a[c], mean_b[c], z[c]);
        s += buf;
    }
    std::snprintf(buf, sizeof buf, "; %dx%d regions x 3 channels, max |z| %.2f; bound |z| <= %.2f (%d tests, false failure < %.2g)",
                  grid, grid, max_region_z, bound, tests, false_failure);
    return s + buf;
}

PathAgreement check_path_agreement(const Image& a, std::uint64_t n_a, const PathSums& b, int grid, double false_failure) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != std::size_t(a.width) * a.height * 3 ||
        b.sum.size() != a.rgb.size() || b.sum_sq.size() != a.rgb.size())
        throw Error("internal: path agreement of images of different sizes");
    if (n_a < 1 || b.spp < 2) throw Error("path agreement needs at least 1 and 2 samples per pixel");
    grid = std::clamp(grid, 1, std::min(a.width, a.height));
    PathAgreement r;
    r.grid = grid;
    r.tests = 3 + 3 * grid * grid;
    r.false_failure = false_failure;
    r.bound = bonferroni_z_bound(false_failure, r.tests);
    const double nb = double(b.spp), scale = 1.0 / double(n_a) + 1.0 / nb;
    const std::size_t cells = std::size_t(grid) * grid;
    // Per region and channel: the two sums of means, the summed variance, the pixel count.
    std::vector<double> da(cells * 3, 0), db(cells * 3, 0), var(cells * 3, 0), count(cells, 0);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t cell = std::size_t(y * grid / a.height) * grid + std::size_t(x * grid / a.width);
            count[cell] += 1;
            for (int c = 0; c < 3; ++c) {
                const std::size_t i = (std::size_t(y) * a.width + x) * 3 + c;
                const double mb = b.sum[i] / nb;
                const double s2 = std::max(0.0, (b.sum_sq[i] - b.sum[i] * mb) / (nb - 1));
                da[cell * 3 + c] += a.rgb[i];
                db[cell * 3 + c] += mb;
                var[cell * 3 + c] += s2;
            }
        }
    auto zscore = [&](double sa, double sb, double v, double n) {
        const double diff = (sa - sb) / n, sd = std::sqrt(v * scale) / n;
        if (diff == 0) return 0.0;
        return sd > 0 ? diff / sd : (diff > 0 ? INFINITY : -INFINITY);
    };
    const double pixels = double(a.width) * a.height;
    for (int c = 0; c < 3; ++c) {
        double sa = 0, sb = 0, v = 0;
        for (std::size_t k = 0; k < cells; ++k) {
            sa += da[k * 3 + c];
            sb += db[k * 3 + c];
            v += var[k * 3 + c];
            const double zk = std::fabs(zscore(da[k * 3 + c], db[k * 3 + c], var[k * 3 + c], count[k]));
            if (!(zk <= r.max_region_z)) {
                r.max_region_z = zk;
                r.worst_region = int(k);
                r.worst_channel = c;
            }
        }
        r.mean_a[c] = sa / pixels;
        r.mean_b[c] = sb / pixels;
        r.z[c] = zscore(sa, sb, v, pixels);
    }
    return r;
}

}  // namespace clpath
