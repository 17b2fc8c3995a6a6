// Adaptive sampling (render/adaptive.hpp): the render stops early where the
// image is easy, each pixel's own count divides its sum, the decisions leave
// the estimate unbiased (and a decision rule that looks at the pixel's value
// is caught), and a resumed render gives the same bits as one that ran through.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/adaptive.hpp"
#include "render/render_session.hpp"
#include "support/render_helpers.hpp"
#include "support/statistics.hpp"
#include "support/temp_paths.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

Scene small_room(int w, int h) { return test::small_cornell(w, h); }

SessionResult adaptive_render(const Scene& scene, RenderSettings st, std::uint64_t spp, double target,
                              std::uint32_t seed = 0) {
    st.seed = seed;
    SessionOptions so;
    so.spp = spp;
    so.noise_target = target;
    return render_session(scene, st, {test::device().device()}, so);
}

TEST(Adaptive, StopsEarlyWithCountsVaryingPerPixel) {
    const Scene scene = small_room(32, 24);
    const SessionResult r = adaptive_render(scene, RenderSettings{}, 4096, 0.2);
    ASSERT_EQ(r.film.pixel_samples().size(), 32u * 24u);
    const auto [least, most] = std::minmax_element(r.film.pixel_samples().begin(), r.film.pixel_samples().end());
    EXPECT_TRUE(r.converged);
    EXPECT_LT(*most, 4096u) << "every pixel met the target before the sample budget";
    EXPECT_LT(*least, *most) << "the counts differ per pixel";
    EXPECT_GE(*least, adaptive_min_samples(0.2));
    // Every pixel met the target, or sits next to one that had not yet.
    for (std::size_t p = 0; p < r.film.pixel_samples().size(); ++p) EXPECT_EQ(r.film.pixel_samples()[p] % 2, 0u);
    // The mean divides each pixel's sum by its own count.
    const Image mean = r.film.mean();
    for (std::size_t p = 0; p < r.film.pixel_samples().size(); ++p)
        EXPECT_EQ(mean.rgb[p * 3], float(fixed_to_double(r.film.sums()[p * 3]) / double(r.film.pixel_samples()[p])));
}

TEST(Adaptive, UniformWithoutAnyStopMatchesAPlainRender) {
    // A target no pixel meets: every pixel takes every sample, and the image is
    // a plain render's, bit for bit (the mask changes which pixels sample, never how).
    const Scene scene = small_room(16, 12);
    SessionOptions so;
    so.spp = 32;
    so.chunk_samples = 2;
    SessionOptions adapt = so;
    adapt.noise_target = 1e-9;
    const SessionResult a = render_session(scene, RenderSettings{}, {test::device().device()}, adapt);
    const SessionResult b = render_session(scene, RenderSettings{}, {test::device().device()}, so);
    ASSERT_EQ(a.film.samples_per_pixel(), 32u);
    for (std::uint32_t n : a.film.pixel_samples()) ASSERT_EQ(n, 32u);
    EXPECT_EQ(a.film.sums(), b.film.sums());
}

TEST(Adaptive, ResumedRenderGivesTheSameBits) {
    const Scene scene = small_room(24, 16);
    const std::string ckpt = test::temp_path("adaptive.ckpt");
    std::filesystem::remove(ckpt);
    SessionOptions so;
    so.spp = 2048;
    so.chunk_samples = 8;
    so.noise_target = 0.08;
    const SessionResult whole = render_session(scene, RenderSettings{}, {test::device().device()}, so);
    // The same render stopped after a few passes, with a checkpoint at every pass boundary.
    SessionOptions first = so;
    first.checkpoint_seconds = 1e-6;
    first.checkpoint_path = ckpt;
    SessionHooks hooks;
    std::uint64_t spp = 0;
    hooks.on_progress = [&](std::uint64_t s) { spp = s; };
    hooks.stop_requested = [&] { return spp >= 200; };
    const SessionResult part = render_session(scene, RenderSettings{}, {test::device().device()}, first, hooks);
    ASSERT_TRUE(part.stopped);
    ASSERT_TRUE(std::filesystem::exists(ckpt));
    SessionOptions rest = so;
    rest.resume_path = ckpt;
    const SessionResult resumed = render_session(scene, RenderSettings{}, {test::device().device()}, rest);
    EXPECT_EQ(resumed.film.sums(), whole.film.sums());
    EXPECT_EQ(resumed.film.half(), whole.film.half());
    EXPECT_EQ(resumed.film.pixel_samples(), whole.film.pixel_samples());
    // Another noise target cannot continue it.
    rest.noise_target = 0.04;
    EXPECT_THROW(render_session(scene, RenderSettings{}, {test::device().device()}, rest), Error);
    std::filesystem::remove(ckpt);
}

// The image mean of each run: a scalar whose spread over runs includes every
// correlation the decisions bring between pixels.
std::vector<double> image_means(const std::vector<Image>& runs) {
    std::vector<double> m;
    for (const Image& img : runs) {
        double s = 0;
        for (float v : img.rgb) s += v;
        m.push_back(s / double(img.rgb.size()));
    }
    return m;
}

// Welch's t of two samples' means.
double welch_t(const std::vector<double>& a, const std::vector<double>& b) {
    auto mv = [](const std::vector<double>& x, double& mean, double& var) {
        mean = 0;
        for (double v : x) mean += v;
        mean /= double(x.size());
        var = 0;
        for (double v : x) var += (v - mean) * (v - mean);
        var /= double(x.size() - 1);
    };
    double ma, va, mb, vb;
    mv(a, ma, va);
    mv(b, mb, vb);
    return (ma - mb) / std::sqrt(va / double(a.size()) + vb / double(b.size()));
}

// Welch-Satterthwaite degrees of freedom of the same.
double welch_dof(const std::vector<double>& a, const std::vector<double>& b) {
    auto var = [](const std::vector<double>& x) {
        double mean = 0, v = 0;
        for (double y : x) mean += y;
        mean /= double(x.size());
        for (double y : x) v += (y - mean) * (y - mean);
        return v / double(x.size() - 1) / double(x.size());
    };
    const double va = var(a), vb = var(b);
    return (va + vb) * (va + vb) /
           (va * va / double(a.size() - 1) + vb * vb / double(b.size() - 1));
}

// A decision rule that looks at the pixel's value: a pixel darker than the
// mean of its 8 neighbours stops (after the minimum). It uses the same
// samples as the real rule, and is biased low: where the image is smooth, a
// pixel is darker than its neighbours when its own estimate happens to be low.
std::vector<std::uint8_t> darker_than_neighbours_stop(const ExactFilm& film, std::uint64_t min_samples) {
    const int w = film.width(), h = film.height();
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    std::vector<double> value(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        value[p] = (fixed_to_double(film.sums()[p * 3]) + fixed_to_double(film.sums()[p * 3 + 1]) +
                    fixed_to_double(film.sums()[p * 3 + 2])) /
                   double(std::max<std::uint64_t>(1, film.samples_of(p)));
    std::vector<std::uint8_t> active(pixels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if ((dx || dy) && nx >= 0 && ny >= 0 && nx < w && ny < h) {
                        sum += value[std::size_t(ny) * w + nx];
                        ++n;
                    }
                }
            const std::size_t p = std::size_t(y) * w + x;
            active[p] = film.samples_of(p) < min_samples || value[p] >= sum / n;
        }
    return active;
}

// The image mean of K adaptive renders against K uniform ones (other seeds):
// Welch's t, with a false-failure rate below 1e-6 (two-sided, at the
// Welch-Satterthwaite degrees of freedom). The control, the biased rule on
// the same seeds, must fail the same test.
TEST(Adaptive, ImageMeanIsUnbiasedAndABiasedRuleIsCaught) {
    const Scene scene = small_room(24, 18);
    constexpr int kRuns = 24;
    constexpr std::uint64_t kSpp = 256;
    std::vector<Image> uniform, adaptive, biased;
    RenderSettings st;
    SessionOptions plain;
    plain.spp = kSpp;
    SessionOptions adapt = plain;
    adapt.noise_target = 0.15;
    SessionOptions wrong = adapt;
    wrong.adaptive_rule = darker_than_neighbours_stop;
    std::uint64_t fewer = 0;
    for (int i = 0; i < kRuns; ++i) {
        st.seed = 5000 + std::uint32_t(i);
        uniform.push_back(render_session(scene, st, {test::device().device()}, plain).film.mean());
        st.seed = 9000 + std::uint32_t(i);
        const SessionResult a = render_session(scene, st, {test::device().device()}, adapt);
        for (std::uint32_t n : a.film.pixel_samples()) fewer += n < kSpp;
        adaptive.push_back(a.film.mean());
        biased.push_back(render_session(scene, st, {test::device().device()}, wrong).film.mean());
    }
    EXPECT_GT(fewer, 0u) << "the noise target stopped no pixel: the test would test nothing";
    const auto mu = image_means(uniform), ma = image_means(adaptive), mb = image_means(biased);
    const double t = welch_t(ma, mu), p = test::student_t_two_sided_p(t, welch_dof(ma, mu));
    const double tb = welch_t(mb, mu), pb = test::student_t_two_sided_p(tb, welch_dof(mb, mu));
    EXPECT_GT(p, 1e-6) << "adaptive image mean differs from uniform: t = " << t;
    EXPECT_LT(pb, 1e-6) << "the biased control rule was not caught: t = " << tb;
    std::printf("adaptive t = %.3f (p %.3g); biased control t = %.3f (p %.3g); %llu pixel-runs stopped early\n", t, p,
                tb, pb, (unsigned long long)fewer);
}

}  // namespace
}  // namespace clpath
