// The thin-lens camera (kernels/camera.cl, camera_lens): what is in the plane
// of focus images as through a pinhole, what is not is blurred, and a
// pinhole draws no random numbers for a lens. The blur's size and weight are
// checked against Mitsuba 3's thinlens sensor in the agreement suite
// (tests/references/mitsuba_agreement_test.cpp, thin-lens).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scene/shapes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"
#include "support/render_runs.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

constexpr float kWallDistance = 5.0f;

// A wall facing the camera kWallDistance away, white with dark vertical bars
// (sharp edges, which a lens focused elsewhere blurs), under a constant sky:
// a diffuse plane sees only the sky, so each of its points has one radiance
// whatever direction it is seen from, and the lens's other viewpoints change
// nothing but where the wall is sharp.
Scene barred_wall() {
    Scene s;
    s.name = "barred-wall";
    const auto white = s.add_material("white", diffuse(glm::vec3(0.8f)));
    const auto dark = s.add_material("dark", diffuse(glm::vec3(0.05f, 0.1f, 0.2f)));
    // make_plane faces +y: turned to face -z, the camera's side.
    const glm::vec3 face_camera(glm::radians(-90.0f), 0, 0);
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, kWallDistance}, face_camera, {20, 1, 20})), white);
    for (int i = -3; i <= 3; ++i)
        s.add_triangles(transformed(make_plane(), shape_transform({0.6f * float(i), 0, kWallDistance - 1e-3f},
                                                                  face_camera, {0.25f, 1, 20})),
                        dark);
    s.environment.color = glm::vec3(1.0f, 0.9f, 0.8f);
    s.camera.eye = {0, 0, 0};
    s.camera.target = {0, 0, 1};
    s.camera.vfov_degrees = 40;
    s.camera.width = 32;
    s.camera.height = 16;
    return s;
}

RenderSettings settings() {
    RenderSettings st;
    st.max_depth = 2;
    return st;
}

// Per pixel and channel, Welch's t-test of the lens's 16 runs against the
// pinhole's 16 (each side's variance from its runs' spread, 15 degrees of
// freedom), Sidak-corrected at 0.01 over the image, as the Mitsuba suite
// does: at least 99.75 % of the values must pass.
test::PixelAgreement agreement(const Scene& pinhole, const Scene& lens) {
    const auto ref = test::reference_from_runs("pinhole", test::render_runs(pinhole, settings(), 16, 16, 100));
    return test::pixel_agreement(test::render_runs(lens, settings(), 16, 16, 200), ref, 0.01, 0.9975);
}

}  // namespace

TEST(ThinLens, PlaneInFocusImagesAsThroughAPinhole) {
    Scene pinhole = barred_wall();
    Scene lens = pinhole;
    lens.camera.aperture_radius = 0.3f;
    lens.camera.focus_distance = kWallDistance;
    const auto r = agreement(pinhole, lens);
    std::fprintf(stderr, "[ thin lens ] focused on the wall: %s\n", r.describe().c_str());
    EXPECT_TRUE(r.ok()) << r.describe();
}

// The control: focused at half the wall's distance, the bars' edges blur
// (a circle of confusion 2 * 0.3 * (5 - 2.5) / 2.5 = 0.6 wide on the wall,
// about 2.6 pixels here).
TEST(ThinLens, PlaneOutOfFocusIsBlurred) {
    Scene pinhole = barred_wall();
    Scene lens = pinhole;
    lens.camera.aperture_radius = 0.3f;
    lens.camera.focus_distance = 0.5f * kWallDistance;
    const auto r = agreement(pinhole, lens);
    std::fprintf(stderr, "[ control ] focused at half the wall's distance: %s\n", r.describe().c_str());
    EXPECT_FALSE(r.ok()) << r.describe();
}

// Focus 0 means the target's distance along the view.
TEST(ThinLens, DefaultFocusIsTheTargetsDistance) {
    Camera c;
    c.eye = {1, 2, 3};
    c.target = {1, 2, 7.5f};
    c.aperture_radius = 0.1f;
    EXPECT_FLOAT_EQ(camera_data(c).focus_distance, 4.5f);
    c.focus_distance = 2;
    EXPECT_FLOAT_EQ(camera_data(c).focus_distance, 2.0f);
    EXPECT_FLOAT_EQ(camera_data(c).lens_radius, 0.1f);
}

// A pinhole's samples are those of a camera that has no lens fields at all:
// its kernel draws no lens sample, so a focus distance changes no bit, and
// the bits differ once the aperture opens.
TEST(ThinLens, PinholeIgnoresTheFocusDistanceBitForBit) {
    Scene s = barred_wall();
    const auto plain = test::render(s, settings(), 4).linear;
    s.camera.focus_distance = 2.5f;
    EXPECT_EQ(test::render(s, settings(), 4).linear.rgb, plain.rgb);
    s.camera.aperture_radius = 1e-3f;
    EXPECT_NE(test::render(s, settings(), 4).linear.rgb, plain.rgb);
}

TEST(ThinLens, BadLensIsRefused) {
    Camera c;
    c.aperture_radius = -1;
    EXPECT_THROW(camera_data(c), Error);
    c.aperture_radius = NAN;
    EXPECT_THROW(camera_data(c), Error);
    c.aperture_radius = 0.1f;
    c.focus_distance = -2;
    EXPECT_THROW(camera_data(c), Error);
}
