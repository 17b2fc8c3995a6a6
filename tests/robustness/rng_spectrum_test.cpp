// The generator through the whole renderer (robustness suite, item 8): images
// of pure noise have a flat power spectrum, and streams of different pixels
// and of successive frames (sample indices) are independent.
//
// The noise image: ambient occlusion of a floor under a parallel ceiling at
// height h, with rays of length D. A cosine-weighted direction reaches the
// ceiling within D when cos(theta) > h / D, which has probability 1 - (h/D)^2
// (the disk projection of Malley's method is uniform), so every sample is
// Bernoulli with p = (h/D)^2, the same for every pixel: an image of 1-spp
// samples is i.i.d. noise if, and only if, the streams are independent.
// For i.i.d. values of variance s2, every periodogram bin |X(k)|^2 / N away
// from the mean (k != 0) has expectation s2 and is exponentially distributed
// (Brockwell & Davis, 10.3); averaged over many bins and frames it is s2 with
// a known standard error. Any correlation between pixels (or frames) at any
// lag shows as a bump or a dip in the spectrum.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "scene/shapes.hpp"
#include "support/render_runs.hpp"
#include "support/statistics.hpp"

using namespace clpath;

namespace {

constexpr int kSize = 64, kFrames = 16;
constexpr double kH = 0.7, kD = 1.0, kP = kH * kH / (kD * kD);

using cd = std::complex<double>;

// In-place radix-2 FFT (Cooley-Tukey); n a power of two.
void fft(std::vector<cd>& a) {
    const std::size_t n = a.size();
    for (std::size_t i = 1, j = 0; i < n; ++i) {
        std::size_t bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(a[i], a[j]);
    }
    for (std::size_t len = 2; len <= n; len <<= 1) {
        const cd w = std::polar(1.0, -2 * M_PI / double(len));
        for (std::size_t i = 0; i < n; i += len) {
            cd wk = 1;
            for (std::size_t k = 0; k < len / 2; ++k, wk *= w) {
                const cd u = a[i + k], v = a[i + k + len / 2] * wk;
                a[i + k] = u + v;
                a[i + k + len / 2] = u - v;
            }
        }
    }
}

// frames[f][y * kSize + x]: the 0/1 sample of pixel (x, y) at sample index f.
std::vector<std::vector<double>> noise_frames() {
    Scene s;
    s.name = "noise";
    const auto grey = s.add_material("grey", diffuse(glm::vec3(0.5f)));
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(1000))), grey);
    s.add_triangles(transformed(make_plane(), shape_transform({0, float(kH), 0}, {0, 0, 0}, glm::vec3(1000))), grey);
    s.camera.eye = {0, 0.35f, 0};
    s.camera.target = {0.1f, 0, 0.05f};
    s.camera.vfov_degrees = 60;
    s.camera.width = s.camera.height = kSize;
    RenderSettings st;
    st.integrator = CLP_INTEGRATOR_AO;
    st.ao_distance = float(kD);
    st.seed = 77;
    Renderer r(test::device(), s, st);
    std::vector<std::vector<double>> frames;
    std::vector<double> prev(kSize * kSize, 0.0);
    for (int f = 1; f <= kFrames; ++f) {
        r.add_samples(1);
        EXPECT_EQ(r.stats().nonfinite, 0u);
        const Image img = r.resolve().linear;
        std::vector<double> sum(kSize * kSize), frame(kSize * kSize);
        // The film's sums of 0/1 values are exact integers; mean * f recovers them.
        for (int i = 0; i < kSize * kSize; ++i) {
            sum[i] = std::round(double(img.rgb[3 * i]) * f);
            frame[i] = sum[i] - prev[i];
            EXPECT_TRUE(frame[i] == 0 || frame[i] == 1) << "pixel " << i << " frame " << f;
        }
        prev = sum;
        frames.push_back(frame);
    }
    return frames;
}

}  // namespace

TEST(RngSpectrum, NoiseImageHasTheExpectedMean) {
    const auto frames = noise_frames();
    double sum = 0;
    for (const auto& f : frames)
        for (double v : f) sum += v;
    const double n = double(kFrames) * kSize * kSize, mean = sum / n;
    EXPECT_NEAR(mean, kP, test::normal_quantile_two_sided(1e-4) * std::sqrt(kP * (1 - kP) / n));
}

// Across pixels: the 2D periodogram of each frame, averaged over frames and
// over 8 x 8 blocks of frequencies (1024 bins per block, minus the DC bin),
// is flat at p (1 - p) in every block; Sidak-corrected over the 64 blocks.
TEST(RngSpectrum, PixelStreamsHaveAFlatSpectrum) {
    const auto frames = noise_frames();
    const double s2 = kP * (1 - kP);
    std::vector<double> power(kSize * kSize, 0.0);
    for (const auto& f : frames) {
        std::vector<std::vector<cd>> rows(kSize, std::vector<cd>(kSize));
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) rows[y][x] = f[y * kSize + x] - kP;
            fft(rows[y]);
        }
        for (int x = 0; x < kSize; ++x) {
            std::vector<cd> col(kSize);
            for (int y = 0; y < kSize; ++y) col[y] = rows[y][x];
            fft(col);
            for (int y = 0; y < kSize; ++y) power[y * kSize + x] += std::norm(col[y]) / (kSize * kSize) / kFrames;
        }
    }
    const int b = 8, blocks = (kSize / b) * (kSize / b);
    const double z = test::normal_quantile_two_sided(1 - std::pow(1 - 0.01, 1.0 / blocks));
    for (int by = 0; by < kSize / b; ++by)
        for (int bx = 0; bx < kSize / b; ++bx) {
            double sum = 0;
            int count = 0;
            for (int y = by * b; y < (by + 1) * b; ++y)
                for (int x = bx * b; x < (bx + 1) * b; ++x) {
                    if (x == 0 && y == 0) continue;  // the mean, tested above
                    sum += power[y * kSize + x];
                    ++count;
                }
            // Each bin, averaged over the frames, has mean s2 and sd s2 / sqrt(frames);
            // a block's bins are independent but for conjugate pairs (k, -k) inside
            // it, which at most double the variance: sd <= s2 sqrt(2 / (count frames)).
            const double mean = sum / count, se = s2 * std::sqrt(2.0 / (count * kFrames));
            EXPECT_NEAR(mean, s2, z * se) << "frequency block (" << bx << ", " << by << ")";
        }
}

// Across frames: for each pixel, the periodogram of its 16 successive
// samples, averaged over the 4096 pixels, is flat at p (1 - p) at every
// frequency 1..15 (a correlation between sample indices at any lag would
// tilt it), Sidak-corrected over the 15 frequencies.
TEST(RngSpectrum, FrameStreamsHaveAFlatSpectrum) {
    const auto frames = noise_frames();
    const double s2 = kP * (1 - kP);
    std::vector<double> power(kFrames, 0.0);
    for (int i = 0; i < kSize * kSize; ++i) {
        std::vector<cd> seq(kFrames);
        for (int f = 0; f < kFrames; ++f) seq[f] = frames[f][i] - kP;
        fft(seq);
        for (int k = 0; k < kFrames; ++k) power[k] += std::norm(seq[k]) / kFrames / (kSize * kSize);
    }
    const double z = test::normal_quantile_two_sided(1 - std::pow(1 - 0.01, 1.0 / (kFrames - 1)));
    for (int k = 1; k < kFrames; ++k) {
        // Bins k and 16 - k are conjugates: the same value, each an average of
        // 4096 independent (Exp-like, sd s2; k = 8 real: chi2_1, sd s2 sqrt 2) values.
        const double se = s2 * (k == kFrames / 2 ? std::sqrt(2.0) : 1.0) / std::sqrt(double(kSize * kSize));
        EXPECT_NEAR(power[k], s2, z * se) << "frame frequency " << k;
    }
}
