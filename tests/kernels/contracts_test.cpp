// The constants and layouts host and kernels both rely on (shared_structs.h)
// read the same on both sides, and the environment distribution the host
// builds is the one the kernels sample.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <unistd.h>

#include "image/image.hpp"
#include "render/environment_map.hpp"
#include "render/light_table.hpp"
#include "shared_structs.h"
#include "support/test_device.hpp"

using namespace clpath;

TEST(Contracts, KernelsSeeTheHostsConstants) {
    Kernel k = test::device().kernel(test::probe_program(), "probe_contracts");
    Buffer ints = test::upload(std::vector<std::uint32_t>(8, 0xdeadbeefu));
    Buffer floats = test::upload(std::vector<float>(5, NAN));
    k.arg(0, ints).arg(1, floats);
    test::run(k, 1);
    const auto i = test::download<std::uint32_t>(ints, 8);
    const auto f = test::download<float>(floats, 5);
    EXPECT_EQ(i[0], CLP_TILE);
    EXPECT_EQ(i[1], CLP_BATCH_TILE);
    EXPECT_EQ(i[2], CLP_BATCH_GRID);
    EXPECT_EQ(i[3], CLP_BATCH_SAMPLES);
    EXPECT_EQ(i[4], CLP_ENV_ROW_CDF(7u, 5u, 3u));
    EXPECT_EQ(i[5], CLP_ENV_CDF_SIZE(7u, 5u));
    EXPECT_EQ(i[6], 0u);
    EXPECT_EQ(i[7], 1u);
    EXPECT_EQ(f[0], CLP_MIN_SPHERICAL_AREA);
    EXPECT_EQ(f[1], CLP_MAX_SPHERICAL_AREA);
    EXPECT_EQ(f[2], CLP_MIN_SPHERICAL_ELEVATION);
    EXPECT_EQ(f[3], CLP_ENV_NOT_SAMPLED);
    EXPECT_EQ(f[4], CLP_MIN_SPHERICAL_SPREAD);
}

namespace {

constexpr int kW = 8, kH = 4;
constexpr std::uint32_t kSamples = 4096;

// An environment image with one texel far brighter than the rest, so that a
// misread distribution shows at once.
std::string write_env_image() {
    Image img;
    img.width = kW;
    img.height = kH;
    img.rgb.assign(std::size_t(kW) * kH * 3, 0.0f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) img.rgb[(std::size_t(y) * kW + x) * 3 + c] = 0.1f * float(1 + x + y * kW);
    for (int c = 0; c < 3; ++c) img.rgb[(std::size_t(1) * kW + 5) * 3 + c] = 50.0f;
    const std::string path =
        (std::filesystem::temp_directory_path() / ("clpath_contracts_env_" + std::to_string(::getpid()) + ".pfm"))
            .string();
    write_pfm(path, img);
    return path;
}

// (d, pdf) of kSamples directions the kernels draw from the host's distribution.
std::vector<cl_float4> sample_on_device(const EnvironmentMap& m) {
    FrameParams fp{};
    fp.env_width = std::uint32_t(m.width);
    fp.env_height = std::uint32_t(m.height);
    fp.env_scale = 1;
    fp.env_rot_cos = 1;
    fp.env_rot_sin = 0;
    Context& ctx = test::device();
    Buffer params = ctx.buffer(sizeof fp, CL_MEM_READ_ONLY, "frame parameters", &fp);
    Buffer pixels = test::upload(m.pixels, "environment image");
    Buffer cdf = test::upload(m.cdf, "environment distribution");
    Buffer out = ctx.buffer(kSamples * sizeof(cl_float4), CL_MEM_READ_WRITE, "samples");
    Kernel k = ctx.kernel(test::probe_program(), "probe_env_sample");
    k.arg(0, params).arg(1, pixels).arg(2, cdf).arg(3, kSamples).arg(4, std::uint32_t(7)).arg(5, out);
    test::run(k, kSamples);
    return test::download<cl_float4>(out, kSamples);
}

}  // namespace

// The pdf the kernels give each sampled direction is the one the test works
// out from the image alone (PBR 4th ed. A.5.6: the texel's share of
// luminance x sin(theta_centre), times w h / (2 pi^2 sin(theta))). A
// distribution the kernels read in another layout than the host wrote gives
// other texels' values.
TEST(Contracts, KernelsSampleTheEnvironmentDistributionTheHostBuilt) {
    const std::string path = write_env_image();
    Environment e;
    e.image = path;
    const EnvironmentMap m = load_environment_map(e);
    ASSERT_EQ(m.cdf.size(), CLP_ENV_CDF_SIZE(std::size_t(kW), std::size_t(kH)));
    const Image img = read_pfm(path);
    std::filesystem::remove(path);
    std::vector<double> f(kW * kH);
    double total = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const glm::vec3 c(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
            f[y * kW + x] = luminance(c) * std::sin(M_PI * (y + 0.5) / kH);
            total += f[y * kW + x];
        }
    const auto s = sample_on_device(m);
    int bright = 0, checked = 0;
    for (const auto& v : s) {
        const double dx = v.s[0], dy = v.s[1], dz = v.s[2];
        const double u = 0.5 + std::atan2(dx, -dz) / (2 * M_PI), t = std::acos(std::clamp(dy, -1.0, 1.0)) / M_PI;
        // Directions on a texel border may round to either side: skipped.
        const double fu = u * kW - std::floor(u * kW), fv = t * kH - std::floor(t * kH);
        if (std::min(fu, 1 - fu) < 1e-3 || std::min(fv, 1 - fv) < 1e-3) continue;
        const int x = std::min(int(u * kW), kW - 1), y = std::min(int(t * kH), kH - 1);
        const double sin_theta = std::sqrt(std::max(0.0, 1 - dy * dy));
        const double expect = f[y * kW + x] / total * kW * kH / (2 * M_PI * M_PI * sin_theta);
        ++checked;
        bright += x == 5 && y == 1;
        // float CDF entries and float trigonometry: a few 1e-6 relative; 1e-3 is far below
        // the ratio between any two texels' values here (>= 1.06).
        ASSERT_NEAR(v.s[3], expect, 1e-3 * expect) << "direction (" << dx << ", " << dy << ", " << dz << ")";
    }
    EXPECT_GT(checked, int(kSamples) * 9 / 10);
    // The bright texel holds most of the luminance: most samples land there.
    EXPECT_GT(bright, checked / 2);
}

// Not importance sampled (the host's CLP_ENV_NOT_SAMPLED marker): the kernels
// sample the sphere uniformly, pdf 1 / 4 pi everywhere.
TEST(Contracts, KernelsSampleUniformlyWhenTheHostSaysSo) {
    const std::string path = write_env_image();
    Environment e;
    e.image = path;
    e.importance_sampled = false;
    const EnvironmentMap m = load_environment_map(e);
    std::filesystem::remove(path);
    ASSERT_EQ(m.cdf.size(), 1u);
    ASSERT_EQ(m.cdf[0], CLP_ENV_NOT_SAMPLED);
    int upper = 0;
    for (const auto& v : sample_on_device(m)) {
        ASSERT_FLOAT_EQ(v.s[3], float(0.25 / M_PI));
        upper += v.s[1] > 0;
    }
    // Half the sphere's directions point up: binomial(4096, 1/2), 6 sigma = 192.
    EXPECT_NEAR(upper, int(kSamples) / 2, 192);
}
