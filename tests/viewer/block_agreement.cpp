#include "viewer/block_agreement.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "support/statistics.hpp"

namespace clpath::test {
namespace {

std::vector<double> block_means(const Image& img, int block, int c) {
    const int bx = img.width / block, by = img.height / block;
    std::vector<double> m(std::size_t(bx) * by, 0.0);
    for (int y = 0; y < by * block; ++y)
        for (int x = 0; x < bx * block; ++x) m[std::size_t(y / block) * bx + x / block] += img.at(x, y, c);
    for (double& v : m) v /= double(block) * block;
    return m;
}

}  // namespace

BlockAgreement compare_blocks(const Image& cand, unsigned cand_spp, const std::vector<Image>& refs, unsigned ref_spp,
                              double alpha, int block) {
    if (refs.size() < 3) throw std::invalid_argument("compare_blocks: need at least 3 references");
    for (const Image& r : refs)
        if (r.width != cand.width || r.height != cand.height)
            throw std::invalid_argument("compare_blocks: image sizes differ");
    const double K = double(refs.size()), nu = K - 1;
    BlockAgreement out;
    out.blocks = (cand.width / block) * (cand.height / block);
    // Bonferroni: three channel tests of each kind, and blocks * 3 for the largest |z|.
    out.z_limit = normal_quantile_two_sided(alpha / (3.0 * out.blocks));
    std::ostringstream rep;
    for (int c = 0; c < 3; ++c) {
        const std::vector<double> v = block_means(cand, block, c);
        std::vector<std::vector<double>> r;
        for (const Image& img : refs) r.push_back(block_means(img, block, c));
        double chi2 = 0;
        for (int b = 0; b < out.blocks; ++b) {
            std::vector<double> samples;
            for (const auto& rb : r) samples.push_back(rb[std::size_t(b)]);
            const MeanError me = mean_error(samples);
            // The floor is float rounding of the sums, for blocks that are
            // exactly constant (all emitter): there the variance is zero.
            const double rounding = 4 * FLT_EPSILON * std::max(std::fabs(me.mean), std::fabs(v[std::size_t(b)]));
            const double se = std::sqrt(me.variance * (double(ref_spp) / cand_spp + 1 / K) + rounding * rounding);
            const double diff = v[std::size_t(b)] - me.mean;
            const double t = se > 0 ? diff / se : 0;
            const double p = std::max(student_t_two_sided_p(t, nu), 1e-300);
            const double z = normal_quantile_two_sided(p);
            chi2 += z * z;
            if (z > out.largest_z) {
                out.largest_z = z;
                rep.str("");
                rep << "worst block " << b << " channel " << c << ": candidate " << v[std::size_t(b)]
                    << ", references " << me.mean << " +- " << se << " (t = " << t << ", z = " << z << "); ";
            }
        }
        out.chi_square_p[c] = chi_square_sf(chi2, out.blocks);
        if (out.chi_square_p[c] < alpha / 3) out.agrees = false;
    }
    if (out.largest_z > out.z_limit) out.agrees = false;
    std::ostringstream full;
    full << rep.str() << "largest |z| " << out.largest_z << " (limit " << out.z_limit << "), chi-square p per channel "
         << out.chi_square_p[0] << ", " << out.chi_square_p[1] << ", " << out.chi_square_p[2] << " (limit "
         << alpha / 3 << ") over " << out.blocks << " blocks";
    out.report = full.str();
    return out;
}

}  // namespace clpath::test
