// The renderer's parts (host/render/): a resize makes a new film and keeps the
// device scene; a film's raw state round-trips bit for bit, so a render can
// stop and go on; one prepared scene uploads to several contexts.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "cl/embedded_sources.hpp"
#include "cl/program.hpp"
#include "render/device_scene.hpp"
#include "render/kernel_features.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "support/render_helpers.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

Scene sized_cornell(int width, int height) {
    Scene s = cornell_thesis_scene();
    s.camera.width = width;
    s.camera.height = height;
    return s;
}

std::size_t film_bytes(int width, int height) {
    std::size_t total = 0;
    for (const auto& [what, bytes] : Film::memory_needs(width, height)) total += bytes;
    return total;
}

void expect_same_image(const RenderedImage& a, const RenderedImage& b) {
    EXPECT_EQ(a.linear.width, b.linear.width);
    EXPECT_EQ(a.linear.height, b.linear.height);
    EXPECT_EQ(a.linear.rgb, b.linear.rgb);
    EXPECT_EQ(a.srgb8, b.srgb8);
}

}  // namespace

TEST(RendererParts, ResizeKeepsTheDeviceSceneAndRendersTheNewSize) {
    RenderSettings st;
    st.seed = 5;
    // The second size is no multiple of the kernels' 8 x 8 tiles.
    const Scene small = sized_cornell(32, 24), large = sized_cornell(45, 29);
    Context ctx(test::device().device());  // its own, so the byte count is this test's alone
    Renderer r(ctx, small, st);
    r.add_samples(3);
    const DeviceScene* scene = &r.device_scene();
    const cl_mem nodes = r.device_scene().nodes().get();
    const std::size_t bytes = ctx.allocated_bytes();

    r.resize(large.camera);
    // The same scene arrays on the device, no second upload: only the film changed.
    EXPECT_EQ(&r.device_scene(), scene);
    EXPECT_EQ(r.device_scene().nodes().get(), nodes);
    EXPECT_EQ(ctx.allocated_bytes(), bytes - film_bytes(32, 24) + film_bytes(45, 29));
    EXPECT_EQ(r.stats().samples_per_pixel, 0u) << "a new film starts with no samples";
    EXPECT_EQ(r.stats().launches, 0u);
    r.add_samples(4);
    expect_same_image(r.resolve(), test::render(large, st, 4));

    // And back: the image of a renderer made at that size.
    r.resize(small.camera);
    EXPECT_EQ(r.device_scene().nodes().get(), nodes);
    EXPECT_EQ(ctx.allocated_bytes(), bytes);
    r.add_samples(4);
    expect_same_image(r.resolve(), test::render(small, st, 4));
}

TEST(RendererParts, AFilmTooLargeLeavesTheRendererAsItWas) {
    RenderSettings st;
    st.seed = 5;
    const Scene small = sized_cornell(16, 16);
    Context ctx(test::device().device());
    Renderer r(ctx, small, st);
    r.add_samples(2);
    // The device made just large enough for what is there and one more film of this size.
    const std::string limit = std::to_string(ctx.allocated_bytes() + film_bytes(16, 16));
    ::setenv("CLPATH_DEVICE_MEMORY_LIMIT", limit.c_str(), 1);
    Camera huge = small.camera;
    huge.width = huge.height = 64;
    try {
        r.resize(huge);
        ADD_FAILURE() << "a film larger than the device's memory was made";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("CLPATH_DEVICE_MEMORY_LIMIT"), std::string::npos) << e.what();
    }
    r.resize(small.camera);  // the same size needs no new film: it always fits
    ::unsetenv("CLPATH_DEVICE_MEMORY_LIMIT");
    EXPECT_EQ(r.camera().width, 16);
    r.add_samples(4);
    expect_same_image(r.resolve(), test::render(small, st, 4));
}

TEST(RendererParts, FilmStateRoundTripsAndTheRenderGoesOn) {
    RenderSettings st;
    st.seed = 9;
    const Scene scene = sized_cornell(24, 16);
    const RenderedImage whole = test::render(scene, st, 7);

    Renderer first(test::device(), scene, st);
    first.add_samples(3);
    const FilmState state = first.film().read_state();
    EXPECT_EQ(state.width, 24);
    EXPECT_EQ(state.height, 16);
    EXPECT_EQ(state.samples_per_pixel, 3u);
    ASSERT_EQ(state.pixels.size(), 24u * 16u);
    bool compensated = false;  // the state carries the Kahan compensation, not only the sums
    for (const AccumPixel& p : state.pixels)
        for (int c = 0; c < 3; ++c) compensated = compensated || p.comp[c] != 0;
    EXPECT_TRUE(compensated) << "no pixel has a compensation term: the round trip would not test it";

    Renderer second(test::device(), scene, st);
    second.film().write_state(state);
    EXPECT_EQ(second.stats().samples_per_pixel, 3u);
    const FilmState again = second.film().read_state();
    EXPECT_EQ(std::memcmp(again.pixels.data(), state.pixels.data(), state.pixels.size() * sizeof(AccumPixel)), 0);
    second.add_samples(4);
    expect_same_image(second.resolve(), whole);

    // Control: the same four samples on a fresh film are another image.
    Renderer fresh(test::device(), scene, st);
    fresh.add_samples(4);
    EXPECT_NE(fresh.resolve().linear.rgb, whole.linear.rgb);

    // A state of another size, or past the sample limit, is refused.
    FilmState wrong = state;
    wrong.width = 16;
    EXPECT_THROW(second.film().write_state(wrong), Error);
    wrong = state;
    wrong.pixels.pop_back();
    EXPECT_THROW(second.film().write_state(wrong), Error);
    wrong = state;
    wrong.samples_per_pixel = kMaxSamplesPerPixel + 1;
    EXPECT_THROW(second.film().write_state(wrong), Error);
}

TEST(RendererParts, OnePreparedSceneOnTwoContexts) {
    RenderSettings st;
    st.seed = 2;
    const auto prepared = prepare_scene(sized_cornell(20, 16), st);
    Context other(test::device().device());
    Renderer a(test::device(), *prepared, st);
    Renderer b(other, *prepared, st);
    a.add_samples(3);
    b.add_samples(3);
    expect_same_image(a.resolve(), b.resolve());
    expect_same_image(a.resolve(), test::render(sized_cornell(20, 16), st, 3));

    // The settings must ask for the structure the scene was prepared with.
    RenderSettings flat = st;
    flat.accel = Accel::Flat;
    EXPECT_THROW(Renderer(other, *prepared, flat), Error);
}

// The scene buffers are bound by position from one table; the kernel's
// parameters come from the same table. Checked on the kernel as compiled,
// through the argument names OpenCL reports.
TEST(DeviceScene, KernelParametersFollowTheSceneBufferTable) {
    RenderSettings st;
    st.all_features = true;
    const KernelFeatures f = kernel_features(SceneFeatures{}, st);
    const BuildResult built = build_program(test::device(), program_source(renderer_kernel_files()),
                                            build_options(f) + " -cl-kernel-arg-info");
    const Kernel k = test::device().kernel(built.program.get(), "render_paths");
    cl_uint args = 0;
    ASSERT_EQ(clGetKernelInfo(k.get(), CL_KERNEL_NUM_ARGS, sizeof args, &args, nullptr), CL_SUCCESS);
    std::vector<std::string> names = scene_buffer_names();
    names.insert(names.end(), {"fp", "accum", "counters", "active"});
    ASSERT_EQ(args, names.size());
    for (cl_uint i = 0; i < args; ++i) {
        char name[64] = {};
        ASSERT_EQ(clGetKernelArgInfo(k.get(), i, CL_KERNEL_ARG_NAME, sizeof name, name, nullptr), CL_SUCCESS);
        EXPECT_EQ(std::string(name), names[i]) << "argument " << i;
    }
}
