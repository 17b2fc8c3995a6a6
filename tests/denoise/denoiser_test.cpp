// Open Image Denoise through clpath's denoiser and guides, on the test device
// (PoCL): a denoised low-sample render must be closer to a high-sample
// reference (pbrt's relative MSE) than the raw estimate it came from, and the
// same criterion must reject a denoised image of another camera (the control:
// a denoiser that returned something smooth but wrong would fail).
// Where the library is missing (tools/install-deps.sh installs it), each test
// says so and is skipped, never passed.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include <glm/glm.hpp>

#include "cl/device_set.hpp"
#include "denoise/denoiser.hpp"
#include "denoise/guides.hpp"
#include "image/compare.hpp"
#include "render/render_session.hpp"
#include "scene/builtin_scenes.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

// The denoiser, or the reason there is none (the test is then skipped).
std::unique_ptr<Denoiser> make_denoiser(std::string& why) {
    try {
        return std::make_unique<Denoiser>();
    } catch (const Error& e) {
        why = e.what();
        return nullptr;
    }
}

#define DENOISER_OR_SKIP(d)                                                                         \
    std::string why;                                                                                \
    auto d = make_denoiser(why);                                                                    \
    if (!d) GTEST_SKIP() << "SKIPPED: Open Image Denoise is not installed, nothing tested: " << why

Scene room(int width, int height) {
    Scene s = cornell_thesis_scene();
    s.camera.width = width;
    s.camera.height = height;
    return s;
}

Image render_mean(const Scene& scene, std::uint64_t spp, std::uint32_t seed) {
    RenderSettings settings;
    settings.seed = seed;
    SessionOptions so;
    so.spp = spp;
    return render_session(scene, settings, select_devices(""), so).film.mean();
}

double relmse(const Image& a, const Image& reference) { return compare_images(a, reference).relmse; }

constexpr int kWidth = 64, kHeight = 48;
constexpr std::uint64_t kLowSamples = 4, kReferenceSamples = 512;

}  // namespace

TEST(Denoiser, LowSampleRenderComesCloserToTheReference) {
    DENOISER_OR_SKIP(denoiser);
    const Scene scene = room(kWidth, kHeight);
    // Independent seeds: the reference's own noise (relMSE about 4/512 of the
    // raw image's) adds alike to both errors.
    const Image reference = render_mean(scene, kReferenceSamples, 1);
    const Image raw = render_mean(scene, kLowSamples, 2);
    const GuideRender guides = render_guides(scene, RenderSettings{}, select_devices(""));
    const Image denoised = denoiser->denoise(raw, &guides.guides);
    const Image colour_only = denoiser->denoise(raw, nullptr);
    const double e_raw = relmse(raw, reference), e_denoised = relmse(denoised, reference),
                 e_colour = relmse(colour_only, reference);
    std::printf("relMSE against %llu spp: raw %llu spp %.5f, denoised with guides %.5f (%.1fx lower), colour "
                "alone %.5f\n",
                (unsigned long long)kReferenceSamples, (unsigned long long)kLowSamples, e_raw, e_denoised,
                e_raw / e_denoised, e_colour);
    EXPECT_LT(e_denoised, e_raw);
    EXPECT_LT(e_colour, e_raw);

    // The control: the same room seen from a camera moved a little; denoised
    // as well, it must be farther from the reference than the raw estimate.
    Scene moved = scene;
    moved.camera.eye += glm::vec3(0.3f, 0.2f, 0.0f) * glm::length(scene.camera.target - scene.camera.eye);
    const Image moved_raw = render_mean(moved, kLowSamples, 2);
    const GuideRender moved_guides = render_guides(moved, RenderSettings{}, select_devices(""));
    const double e_moved = relmse(denoiser->denoise(moved_raw, &moved_guides.guides), reference);
    std::printf("control: denoised image of a moved camera: relMSE %.5f\n", e_moved);
    EXPECT_GT(e_moved, e_raw) << "the criterion does not tell another camera's image from this one's";
}

// The guides are the albedo and normals views of the estimate's camera, rays
// and seed: the same bits as those views rendered on their own.
TEST(Denoiser, GuidesAreTheViewsOfTheSameCamera) {
    const Scene scene = room(kWidth, kHeight);
    RenderSettings settings;
    settings.seed = 3;
    const GuideRender g = render_guides(scene, settings, select_devices(""), 16);
    const auto view = [&](std::uint32_t integrator) {
        RenderSettings s = settings;
        s.integrator = integrator;
        SessionOptions so;
        so.spp = 16;
        return render_session(scene, s, select_devices(""), so).film.mean();
    };
    EXPECT_EQ(g.guides.albedo.rgb, view(CLP_INTEGRATOR_ALBEDO).rgb);
    EXPECT_EQ(g.guides.normal.rgb, decode_normals_view(view(CLP_INTEGRATOR_NORMALS)).rgb);
    EXPECT_TRUE(g.guides.clean);
    ASSERT_EQ(g.guides.albedo.width, kWidth);
    ASSERT_EQ(g.guides.normal.height, kHeight);
}

TEST(Denoiser, GuidesOfAnotherSizeAreRefused) {
    DENOISER_OR_SKIP(denoiser);
    Image colour{8, 8, std::vector<float>(8 * 8 * 3, 0.5f)};
    DenoiseGuides guides;
    guides.albedo = Image{8, 4, std::vector<float>(8 * 4 * 3, 0.5f)};
    guides.normal = colour;
    try {
        denoiser->denoise(colour, &guides);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the albedo guide is 8x4, the image 8x8"), std::string::npos) << e.what();
    }
}

TEST(Denoiser, NormalsViewDecodesToUnitRange) {
    Image view{2, 1, {0.5f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    const Image n = decode_normals_view(view);
    EXPECT_EQ(n.rgb, (std::vector<float>{0.0f, 1.0f, -1.0f, -1.0f, -1.0f, -1.0f}));
}
