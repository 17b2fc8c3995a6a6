// Light transport on hard cases (robustness suite, item 6): each with its
// expected result; zero non-finite samples in all.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/shapes.hpp"
#include "support/analytic_scenes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"
#include "support/render_runs.hpp"
#include "support/statistics.hpp"

using namespace clpath;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<glm::vec3> quad(glm::vec3 centre, glm::vec3 rotation, glm::vec3 size) {
    return transformed(make_plane(), shape_transform(centre, rotation, size));
}

// Both light-transport integrators (paths of up to 6 bounces) must render
// exactly 0 everywhere.
void expect_dark(const Scene& s, std::uint32_t spp) {
    RenderSettings st;
    st.max_depth = 6;
    for (auto integrator : test::kLightTransportIntegrators) {
        st.integrator = integrator;
        test::expect_every_value(s, st, spp, 0.0f);
    }
}

}  // namespace

// A one-sided emitter facing up, above a floor, nothing above it. Expected:
// exactly 0 everywhere for both light-transport integrators (its back faces
// the floor and emits nothing, light sampling sees cos <= 0), and exactly Le
// where the camera sees its front.
TEST(LightTransportHard, EmitterFacingAwayLightsNothing) {
    Scene s;
    s.name = "away";
    s.add_triangles(quad({0, 0, 0}, {0, 0, 0}, {10, 1, 10}), s.add_material("floor", diffuse(glm::vec3(0.8f))));
    s.add_triangles(quad({0, 1, 0}, {0, 0, 0}, {1, 1, 1}), s.add_material("lamp", emitter(glm::vec3(5.0f))));
    s.camera.eye = {0.2f, 0.5f, -3};
    s.camera.target = {0, 0.2f, 0};
    s.camera.width = s.camera.height = 16;
    expect_dark(s, 32);
    s.camera.eye = {0.1f, 3, 0.05f};  // above, looking down at the lamp's front
    s.camera.target = {0, 1, 0};
    s.camera.vfov_degrees = 10;
    RenderSettings st;
    st.max_depth = 6;
    test::expect_every_value(s, st, 4, 5.0f);
}

// A 1e-2-wide lamp of radiance 4e4 (the power of a 1-unit lamp of 4) one
// unit above a floor of albedo rho: the floor below has radiance
// rho/pi Le A (1 - side^2/3) (the cos cos / r^2 of the small source averaged
// over it). Next-event estimation finds it at every sample;
// BSDF sampling hits it rarely and brightly (fireflies): both means must be
// right within their standard errors, and nothing non-finite.
TEST(LightTransportHard, TinyBrightLight) {
    const double side = 1e-2, le = 4e4, rho = 0.5;
    Scene s;
    s.name = "tiny";
    s.add_triangles(quad({0, 0, 0}, {0, 0, 0}, {100, 1, 100}), s.add_material("floor", diffuse(glm::vec3(rho))));
    s.add_triangles(quad({0, 1, 0}, {float(kPi), 0, 0}, glm::vec3(float(side))),
                    s.add_material("lamp", emitter(glm::vec3(float(le)))));
    s.camera.eye = {0, 0.5f, -1};
    s.camera.target = {0, 0, 0};
    s.camera.vfov_degrees = 0.01f;  // every sample lands within 1e-4 of the point below the lamp
    s.camera.width = s.camera.height = 8;
    const double expected = rho / kPi * le * side * side * (1 - side * side / 3);
    for (auto integrator : test::kLightTransportIntegrators) {
        RenderSettings st;
        st.integrator = integrator;
        st.max_depth = 1;
        // BSDF sampling hits the lamp with probability ~ A / pi = 3e-5: a
        // handful of hits per pixel, so the mean over all pixels is tested
        // (pixels are independent), about 130 hits in all.
        const std::uint32_t spp = integrator == CLP_INTEGRATOR_PATH ? 16 : (1u << 16);
        RenderStats stats;
        const auto img = test::render(s, st, spp, &stats).linear;
        EXPECT_EQ(stats.nonfinite, 0u);
        const auto m = test::mean_error(test::channel(img, 0));
        if (integrator == CLP_INTEGRATOR_PATH) {
            // Light sampling of a 1e-2 square from 1 away: the sampled
            // geometry term varies by ~1e-4; mean of 1024 samples.
            EXPECT_NEAR(m.mean, expected, 4.4 * m.std_error + 1e-5 * expected);
        } else {
            // Per pixel the count of hits is Poisson; pixels give the mean and its error.
            EXPECT_NEAR(m.mean, expected, 4.4 * m.std_error) << integrator_name(integrator) << " +- " << m.std_error;
            EXPECT_GT(m.mean, 0.0) << "BSDF sampling should have hit the lamp";
        }
    }
}

namespace {
// An object in a constant sky (a furnace): every path that leaves reaches Le.
Scene sky_with(const std::vector<std::pair<std::vector<glm::vec3>, SceneMaterial>>& parts, glm::vec3 eye) {
    Scene s;
    s.name = "sky";
    int i = 0;
    for (const auto& [tris, m] : parts)
        s.add_triangles(tris, s.add_material(std::string("m").append(std::to_string(i++)), m));
    s.environment.color = glm::vec3(0.8f, 0.5f, 0.3f);
    s.camera.eye = eye;
    s.camera.target = {0, 0, 0};
    s.camera.vfov_degrees = 40;
    s.camera.width = s.camera.height = 16;
    return s;
}

}  // namespace

// Glass inside glass: a sphere of relative index 1.2 inside one of 1.5
// (absolute 1.8 inside 1.5 inside 1), both clear. Refractions scale radiance
// by (n_i/n_t)^2 and these telescope along any path that leaves, so from
// outside every pixel's expectation is the sky exactly (roulette and the
// 64-bounce limit aside: paths trapped that long are < 1e-6 of the total).
TEST(LightTransportHard, GlassInsideGlassConservesEnergy) {
    const Scene s = sky_with({{transformed(make_icosphere(3), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(1))),
                               dielectric(1.5f)},
                              {transformed(make_icosphere(2), shape_transform({0.1f, 0, 0}, {0, 0, 0}, glm::vec3(0.5f))),
                               dielectric(1.2f)}},
                             {0, 0, -4});
    for (auto integrator : test::kLightTransportIntegrators) test::expect_sky_furnace(s, 1.0, integrator, 0);
}

// A light inside glass: an emitting sphere inside a glass shell, on a floor.
// Light sampling cannot see through glass (shadow rays stop at it), so all of
// the light arrives through BSDF-sampled paths; next-event estimation with
// MIS and BSDF sampling alone must give the same image.
TEST(LightTransportHard, LightInsideGlass) {
    Scene s;
    s.name = "lamp-in-glass";
    s.add_triangles(quad({0, 0, 0}, {0, 0, 0}, {10, 1, 10}), s.add_material("floor", diffuse(glm::vec3(0.7f))));
    s.add_triangles(transformed(make_icosphere(2), shape_transform({0, 0.6f, 0}, {0, 0, 0}, glm::vec3(0.5f))),
                    s.add_material("glass", dielectric(1.5f)));
    s.add_triangles(transformed(make_icosphere(1), shape_transform({0, 0.6f, 0}, {0, 0, 0}, glm::vec3(0.2f))),
                    s.add_material("lamp", emitter(glm::vec3(8.0f))));
    s.camera.eye = {0, 1.2f, -2.5f};
    s.camera.target = {0, 0.3f, 0};
    s.camera.vfov_degrees = 45;
    s.camera.width = s.camera.height = 24;
    RenderSettings st;
    st.max_depth = 6;
    std::uint64_t nonfinite = 0;
    const auto a = test::render_runs(s, st, 32, 8, 10, &nonfinite);
    st.integrator = CLP_INTEGRATOR_PATH_BSDF;
    const auto b = test::render_runs(s, st, 32, 8, 20, &nonfinite);
    EXPECT_EQ(nonfinite, 0u);
    const auto r = test::pixel_agreement(a, test::reference_from_runs("path-bsdf", b));
    EXPECT_TRUE(r.ok()) << r.describe();
}

// Total internal reflection: the camera inside a glass block (n = 1.5,
// critical angle 41.81 deg) looks at the top face at 40 and 43 degrees of
// incidence, with one bounce allowed. At 43: every sample reflects (TIR)
// into the block and ends: exactly 0. At 40: a sample refracts out with
// probability 1 - F and carries n^2 Le (radiance is squeezed into the
// denser medium), so the mean is n^2 Le (1 - F(40 deg)), F the unpolarised
// Fresnel reflectance computed here in double.
TEST(LightTransportHard, TotalInternalReflection) {
    const double n = 1.5, le = 1.0;
    for (double deg : {40.0, 43.0}) {
        Scene s;
        s.name = "tir";
        s.add_triangles(transformed(make_box(), shape_transform({0, 0, 0}, {0, 0, 0}, {100, 2, 100})),
                        s.add_material("glass", dielectric(float(n))));
        s.environment.color = glm::vec3(float(le));
        const double a = deg * kPi / 180;
        s.camera.eye = {0, 0, 0};
        s.camera.target = {float(std::sin(a)), float(std::cos(a)), 0};
        s.camera.up = {0, 0, 1};
        s.camera.vfov_degrees = 0.01f;
        s.camera.width = s.camera.height = 8;
        RenderSettings st;
        st.max_depth = 1;
        st.rr_rule = CLP_RR_NONE;
        RenderStats stats;
        const auto img = test::render(s, st, 256, &stats).linear;
        EXPECT_EQ(stats.nonfinite, 0u);
        const auto m = test::mean_error(test::channel(img, 0));
        if (deg > 41.81) {
            EXPECT_EQ(test::nonzero(img), 0u) << deg << " degrees: total internal reflection lets nothing out";
            continue;
        }
        const double ci = std::cos(a), st2 = n * n * (1 - ci * ci), ct = std::sqrt(1 - st2);
        const double eta = 1 / n;  // n_t / n_i leaving the glass
        const double rpar = (eta * ci - ct) / (eta * ci + ct), rperp = (ci - eta * ct) / (ci + eta * ct);
        const double F = 0.5 * (rpar * rpar + rperp * rperp);
        EXPECT_NEAR(m.mean, n * n * le * (1 - F), 4.4 * m.std_error + 1e-3) << deg << " degrees, F = " << F;
    }
}

// The camera inside a closed opaque box, sky and sun outside: every pixel is
// exactly 0 for every integrator that transports light.
TEST(LightTransportHard, CameraInsideClosedObjectSeesNothing) {
    Scene s;
    s.name = "inside";
    s.add_triangles(transformed(make_icosphere(3), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(2))),
                    s.add_material("shell", diffuse(glm::vec3(0.9f))));
    s.environment.color = glm::vec3(3.0f);
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.intensity = glm::vec3(5.0f);
    s.lights = {sun};
    s.camera.eye = {0.3f, -0.2f, 0.1f};
    s.camera.target = {1, 0.5f, 0.2f};
    s.camera.vfov_degrees = 90;
    s.camera.width = s.camera.height = 16;
    expect_dark(s, 64);
}

namespace {
// The integer room (closed, lit by its lamp under the ceiling, the camera
// inside) with a constant sky of radiance `sky` outside.
Scene closed_room(float sky) {
    Scene s = test::integer_room();
    s.environment.color = glm::vec3(sky);
    return s;
}
}  // namespace

// No sky light enters a closed room, so a sky outside must leave the image's
// expectation unchanged, only noisier. With the sky in the light table,
// next-event estimation picks the lamp with probability 0.26 instead of 1
// (picks of the sky end in a blocked shadow ray), and MIS weighs the lamp's
// BSDF-sampled hits by that probability: a selection probability used
// inconsistently between the two would make the room darker or brighter.
// The whole image's mean is z-tested per channel (one 32-pixel block, false
// failure rate 1e-6 in all). Its standard error is about 0.12 % of the mean,
// so a shift of 0.75 % fails (z about 6). Control: a lamp 1 % dimmer is
// rejected. With one light and the same seeds the image is linear in the
// lamp's emission, so the control scales the images instead of re-rendering.
TEST(LightTransportHard, SkyOutsideClosedRoomChangesNothing) {
    RenderSettings st;
    st.max_depth = 6;
    std::uint64_t nonfinite = 0;
    const auto dark = test::render_runs(closed_room(0.0f), st, 512, 4, 30, &nonfinite);
    const auto sky = test::render_runs(closed_room(1.0f), st, 512, 4, 40, &nonfinite);
    EXPECT_EQ(nonfinite, 0u);
    const auto r = test::image_agreement(dark, sky, 32, 1e-6);
    EXPECT_TRUE(r.ok()) << r.describe();
    auto dimmer = dark;
    for (auto& img : dimmer)
        for (float& v : img.rgb) v *= 0.99f;
    const auto c = test::image_agreement(dimmer, sky, 32, 1e-6);
    EXPECT_FALSE(c.ok()) << "a 1 % dimmer lamp passed: " << c.describe();
}
