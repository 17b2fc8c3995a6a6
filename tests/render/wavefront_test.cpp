// The wavefront kernels (kernels/wavefront.cl) against the megakernel
// (kernels/integrator.cl): the same estimator, random streams and film, so on
// one device, where the compiler emits the same arithmetic for both, the same
// image bit for bit and the same ray count, on every bundled scene and both
// light-transport integrators. (Where bits cannot match, on another device,
// the agreement tests run again under CLPATH_KERNEL=wavefront: tests/CMakeLists.txt.)
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/builtin_scenes.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"
#include "support/repo_root.hpp"
#include "support/render_helpers.hpp"

using namespace clpath;
namespace fs = std::filesystem;

namespace {

using test::repo_root;

// Every scene file shipped in scenes/ (JSON and the glTF model).
std::vector<std::string> bundled_scenes() {
    std::vector<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(repo_root() / "scenes")) {
        const std::string ext = e.path().extension().string();
        if (ext == ".json" || ext == ".gltf") files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

struct Rendered {
    Image image;
    RenderStats stats;
};

Rendered render_shape(const Scene& scene, RenderSettings st, KernelShape shape, std::uint32_t spp) {
    st.kernel_shape = shape;
    Rendered out;
    out.image = test::render(scene, st, spp, &out.stats).linear;
    return out;
}

Scene small(const std::string& file) {
    Scene s = load_scene(file);
    s.camera.width = 24;
    s.camera.height = 16;
    return s;
}

}  // namespace

TEST(Wavefront, SameBitsAsTheMegakernelOnEveryBundledScene) {
    const auto files = bundled_scenes();
    ASSERT_GE(files.size(), 10u) << "scenes/ not found above " << fs::current_path();
    std::size_t renders = 0, black = 0;
    for (const std::string& file : files) {
        const Scene s = small(file);
        for (std::uint32_t integrator : test::kLightTransportIntegrators) {
            SCOPED_TRACE(file + ", " + integrator_name(integrator));
            RenderSettings st = settings_from_scene(s.render);
            st.integrator = integrator;
            st.seed = 11;
            const Rendered mega = render_shape(s, st, KernelShape::Mega, 3);
            const Rendered wave = render_shape(s, st, KernelShape::Wavefront, 3);
            ++renders;
            black += test::nonzero(mega.image) == 0;  // a point light by BSDF sampling alone, say
            EXPECT_EQ(wave.image.rgb, mega.image.rgb);
            EXPECT_EQ(wave.stats.rays, mega.stats.rays);
            EXPECT_EQ(wave.stats.nonfinite, mega.stats.nonfinite);
        }
    }
    EXPECT_LE(black * 4, renders) << "black images agree whatever the kernels do";
}

// A thin lens draws its two numbers after the pixel jitter in both shapes.
// The light BVH forced on where Auto picks by power (and on a city of lamps):
// both shapes pick the same lights with the same pmfs and weigh BSDF hits by
// the same normal, kept in 32 bits by both (path.cl, PathState.prev_n).
TEST(Wavefront, SameBitsWithTheLightBvh) {
    std::vector<Scene> scenes;
    for (const char* f : {"scenes/cornell-classic.json", "scenes/textured/textured.json", "scenes/hard/tiny-light.json"})
        scenes.push_back(small((repo_root() / f).string()));
    Scene city = night_city_scene(200);
    city.camera.width = 24;
    city.camera.height = 16;
    scenes.push_back(city);
    for (const Scene& s : scenes) {
        SCOPED_TRACE(s.name);
        RenderSettings st = settings_from_scene(s.render);
        st.light_sampler = LightSampler::Bvh;
        st.seed = 5;
        const Rendered mega = render_shape(s, st, KernelShape::Mega, 4);
        const Rendered wave = render_shape(s, st, KernelShape::Wavefront, 4);
        EXPECT_GT(test::nonzero(mega.image), 0u);
        EXPECT_EQ(wave.image.rgb, mega.image.rgb);
        EXPECT_EQ(wave.stats.rays, mega.stats.rays);
    }
}

TEST(Wavefront, SameBitsWithAThinLens) {
    const Scene s = small((repo_root() / "benchmarks" / "references" / "scenes" / "thin-lens.json").string());
    ASSERT_TRUE(s.camera.has_lens());
    for (std::uint32_t integrator : test::kLightTransportIntegrators) {
        SCOPED_TRACE(integrator_name(integrator));
        RenderSettings st = settings_from_scene(s.render);
        st.integrator = integrator;
        st.seed = 5;
        const Rendered mega = render_shape(s, st, KernelShape::Mega, 3);
        const Rendered wave = render_shape(s, st, KernelShape::Wavefront, 3);
        EXPECT_GT(test::nonzero(mega.image), 0u);
        EXPECT_EQ(wave.image.rgb, mega.image.rgb);
        EXPECT_EQ(wave.stats.rays, mega.stats.rays);
    }
}

// The control: the comparison sees a one-sample difference.
TEST(Wavefront, AnotherSampleCountDiffers) {
    const Scene s = test::small_cornell(24, 16);
    RenderSettings st;
    const Rendered mega = render_shape(s, st, KernelShape::Mega, 3);
    const Rendered wave = render_shape(s, st, KernelShape::Wavefront, 4);
    EXPECT_NE(wave.image.rgb, mega.image.rgb);
}

// Samples added in several calls (several waves per launch, several launches)
// sum to the image of one call, as the megakernel's do.
TEST(Wavefront, LaunchSplitDoesNotMatter) {
    const Scene s = test::small_cornell(40, 32);
    RenderSettings st;
    st.seed = 3;
    st.kernel_shape = KernelShape::Wavefront;
    const Image whole = test::render(s, st, 6).linear;
    Renderer r(test::device(), s, st);
    for (int i = 0; i < 3; ++i) r.add_samples(2);
    EXPECT_EQ(r.resolve().linear.rgb, whole.rgb);
}

// Switching shapes on one renderer rebuilds its program (and, as any change
// of settings, starts a new image): the new shape's image is the same bits.
TEST(Wavefront, ShapeSwitchRebuildsTheProgram) {
    const Scene s = test::small_cornell(24, 16);
    RenderSettings st;
    st.seed = 5;
    st.kernel_shape = KernelShape::Mega;
    Renderer r(test::device(), s, st);
    r.add_samples(4);
    const Image mega = r.resolve().linear;
    st.kernel_shape = KernelShape::Wavefront;
    r.set_settings(st);
    r.add_samples(4);
    EXPECT_EQ(r.resolve().linear.rgb, mega.rgb);
    EXPECT_GT(test::nonzero(mega), 0u);
}

TEST(Wavefront, OneBounceViewsAreRefusedByName) {
    RenderSettings st;
    st.integrator = CLP_INTEGRATOR_AO;
    st.kernel_shape = KernelShape::Wavefront;
    try {
        validate_settings(st);
        FAIL() << "the wavefront has no ambient occlusion";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'ao'"), std::string::npos) << e.what();
    }
    st.kernel_shape = KernelShape::Auto;
    EXPECT_EQ(resolve_kernel_shape(st, true), KernelShape::Mega);
    st.integrator = CLP_INTEGRATOR_PATH;
    EXPECT_EQ(resolve_kernel_shape(st, true), KernelShape::Mega);  // measured faster on GPUs and CPUs
    st.kernel_shape = KernelShape::Wavefront;
    EXPECT_EQ(resolve_kernel_shape(st, false), KernelShape::Wavefront);
}
