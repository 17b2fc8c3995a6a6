// The flat structure (--accel flat) changes how hits are found, not which:
// with the same seed the image is the BVH's, bit for bit (the integrator is
// the same code and every ray gets the same closest hit).
#include <gtest/gtest.h>

#include "scene/builtin_scenes.hpp"
#include "support/render_helpers.hpp"
#include "util/error.hpp"

using namespace clpath;

TEST(AccelRender, FlatGivesTheBvhImage) {
    Scene scene = cornell_thesis_scene();
    scene.camera.width = 48;
    scene.camera.height = 40;
    RenderSettings bvh = settings_from_scene(scene.render);
    bvh.seed = 7;
    RenderSettings flat = bvh;
    flat.accel = Accel::Flat;
    const RenderedImage a = test::render(scene, bvh, 4);
    const RenderedImage b = test::render(scene, flat, 4);
    ASSERT_EQ(a.linear.rgb.size(), b.linear.rgb.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.linear.rgb.size(); ++i) differ += a.linear.rgb[i] != b.linear.rgb[i];
    EXPECT_EQ(differ, 0u) << "of " << a.linear.rgb.size() << " channel values";
}

TEST(AccelRender, AccelCannotChangeInARunningRenderer) {
    Scene scene = cornell_thesis_scene();
    scene.camera.width = 8;
    scene.camera.height = 8;
    RenderSettings s = settings_from_scene(scene.render);
    Renderer r(test::device(), scene, s);
    s.accel = Accel::Flat;
    EXPECT_THROW(r.set_settings(s), Error);
}
