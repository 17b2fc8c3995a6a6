// Convergence: the mean squared error against a high-sample render of the same
// scene falls as 1/spp. With per-sample variance s2 (averaged over pixels),
// E[MSE(n)] = s2/n + s2/N for a reference of N samples, so
// k(n) = MSE(n) / (1/n + 1/N) must be the same for every n; each k is
// compared with its standard error, estimated from the pixels' squared errors.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/builtin_scenes.hpp"
#include "support/render_helpers.hpp"
#include "support/statistics.hpp"

using namespace clpath;

TEST(Convergence, MseFallsAsOneOverSpp) {
    Scene s = cornell_thesis_scene();
    s.camera.width = 48;
    s.camera.height = 40;
    RenderSettings st;
    st.max_depth = 6;
    const std::uint32_t N = 2048;
    st.seed = 1000;
    const Image ref = test::render(s, st, N).linear;

    struct Point {
        double n, k, se;
    };
    std::vector<Point> points;
    for (std::uint32_t n : {4u, 16u, 64u}) {
        st.seed = n;  // independent of the reference and of each other
        const Image img = test::render(s, st, n).linear;
        std::vector<double> sq(img.rgb.size());
        for (std::size_t i = 0; i < sq.size(); ++i) sq[i] = std::pow(double(img.rgb[i]) - ref.rgb[i], 2);
        const auto m = test::mean_error(sq);
        const double scale = 1.0 / n + 1.0 / N;
        points.push_back({double(n), m.mean / scale, m.std_error / scale});
    }
    const double z = test::normal_quantile_two_sided(1e-4 / 3);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = i + 1; j < points.size(); ++j) {
            const auto& a = points[i];
            const auto& b = points[j];
            EXPECT_NEAR(a.k, b.k, z * std::hypot(a.se, b.se))
                << "spp " << a.n << " vs " << b.n << ": MSE*spp " << a.k << " +- " << a.se << " vs " << b.k << " +- "
                << b.se;
        }
    // And the errors do fall: MSE(64) well below MSE(4).
    EXPECT_LT(points[2].k * (1.0 / 64 + 1.0 / N), points[0].k * (1.0 / 4 + 1.0 / N) / 4);
}
