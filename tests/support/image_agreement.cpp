#include "support/image_agreement.hpp"

#include <cmath>
#include <cstdio>
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

Reference reference_from_runs(const std::string& name, const std::vector<Image>& runs) {
    const PixelStats s = pixel_stats(runs);
    Reference r;
    r.name = name;
    r.mean = runs[0];
    for (std::size_t i = 0; i < s.mean.size(); ++i) r.mean.rgb[i] = float(s.mean[i]);
    r.var_of_mean = s.var_of_mean;
    r.dof = double(runs.size()) - 1;
    return r;
}

Reference reference_exact(const std::string& name, const Image& image) {
    Reference r;
    r.name = name;
    r.mean = image;
    return r;
}

Reference reference_from_sample_count(const std::string& name, const Image& image, double samples,
                                      const std::vector<Image>& runs, double spp_per_run) {
    const PixelStats s = pixel_stats(runs);
    if (image.rgb.size() != s.mean.size()) throw std::invalid_argument("reference: sizes differ");
    Reference r;
    r.name = name;
    r.mean = image;
    // var of one run's mean = s2 / spp  =>  s2 = var_of_mean * K * spp.
    const double k = double(runs.size());
    r.var_of_mean.resize(s.mean.size());
    for (std::size_t i = 0; i < s.mean.size(); ++i) r.var_of_mean[i] = s.var_of_mean[i] * k * spp_per_run / samples;
    r.dof = k - 1;
    return r;
}

PixelAgreement pixel_agreement(const std::vector<Image>& runs, const Reference& ref, double alpha, double required,
                               double rounding_rel) {
    const PixelStats s = pixel_stats(runs);
    const int w = runs[0].width, h = runs[0].height;
    if (ref.mean.width != w || ref.mean.height != h || ref.mean.rgb.size() != s.mean.size())
        throw std::invalid_argument("pixel_agreement: the reference '" + ref.name + "' has another size");
    if (!ref.var_of_mean.empty() && ref.var_of_mean.size() != s.mean.size())
        throw std::invalid_argument("pixel_agreement: variance size differs");
    PixelAgreement r;
    r.reference = ref.name;
    r.required = required;
    r.values = int(s.mean.size());
    r.alpha_value = 1 - std::pow(1 - alpha, 1.0 / r.values);
    const double dof_runs = double(runs.size()) - 1;
    if (!ref.run_var_of_mean.empty() && ref.run_var_of_mean.size() != s.mean.size())
        throw std::invalid_argument("pixel_agreement: known variance size differs");
    for (std::size_t i = 0; i < s.mean.size(); ++i) {
        const double m_ref = ref.mean.rgb[i];
        const bool known = !ref.run_var_of_mean.empty();
        const double va = known ? ref.run_var_of_mean[i] : s.var_of_mean[i];
        const double vb = ref.var_of_mean.empty() ? 0.0 : ref.var_of_mean[i];
        const double dof_a = known ? INFINITY : dof_runs;
        const double diff = s.mean[i] - m_ref;
        double p;
        if (!std::isfinite(s.mean[i]) || !std::isfinite(m_ref)) {
            p = 0;
        } else if (std::fabs(diff) <= rounding_rel * std::fabs(m_ref)) {
            p = 1;
        } else if (va + vb > 0) {
            const double den = (va > 0 ? va * va / dof_a : 0.0) + (vb > 0 ? vb * vb / ref.dof : 0.0);
            const double dof = den > 0 ? (va + vb) * (va + vb) / den : INFINITY;
            p = student_t_two_sided_p(diff / std::sqrt(va + vb), dof);
        } else {
            p = 0;  // different, and neither side varies
        }
        if (p <= r.alpha_value) ++r.failed;
        if (p < r.worst_p) {
            r.worst_p = p;
            r.worst_c = int(i % 3);
            r.worst_x = int(i / 3 % std::size_t(w));
            r.worst_y = int(i / 3 / std::size_t(w));
        }
    }
    return r;
}

std::string PixelAgreement::describe() const {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "against '%s': %d of %d pixel values fail at the Sidak-corrected level %.3g (%.3f%% pass, %.2f%% "
                  "required); worst p %.3g at (%d, %d) channel %d",
                  reference.c_str(), failed, values, alpha_value, 100 * pass_fraction(), 100 * required, worst_p,
                  worst_x, worst_y, worst_c);
    return buf;
}

std::string Agreement::describe() const {
    return std::to_string(failed) + " of " + std::to_string(blocks) + " blocks differ (critical z " +
           std::to_string(critical_z) + ", worst z " + std::to_string(worst_z) + " at (" + std::to_string(worst_x) +
           ", " + std::to_string(worst_y) + "))";
}

}  // namespace clpath::test
