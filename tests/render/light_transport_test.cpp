// Light transport against closed-form answers and against itself: furnaces
// for every material, delta lights against their analytic radiance, ambient
// occlusion against its integral, and statistical equality of estimators that
// must agree (NEE + MIS vs BSDF sampling, environment importance sampling vs
// uniform, specialised vs all-features kernels).
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#ifdef CLPATH_WITH_OIIO
#include <OpenImageIO/imageio.h>
#endif

#include "render/environment_map.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/shapes.hpp"
#include "support/analytic_scenes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"
#include "support/render_runs.hpp"
#include "support/statistics.hpp"
#include "support/temp_paths.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Image> runs(const Scene& scene, const RenderSettings& st, std::uint32_t spp, int k, std::uint32_t seed0) {
    std::uint64_t nonfinite = 0;
    auto out = test::render_runs(scene, st, spp, k, seed0, &nonfinite);
    EXPECT_EQ(nonfinite, 0u);
    return out;
}

// An object of one material under a constant white-ish sky.
Scene sky_furnace(const SceneMaterial& m, glm::vec3 le, bool camera_inside) {
    Scene s;
    s.name = "sky-furnace";
    const auto id = s.add_material("object", m);
    s.add_triangles(make_icosphere(2), id);
    s.environment.color = le;
    s.camera.eye = camera_inside ? glm::vec3(0.1f, 0.05f, -0.2f) : glm::vec3(0, 0, -3);
    s.camera.target = {0, 0, 1};
    s.camera.vfov_degrees = camera_inside ? 60 : 40;
    s.camera.width = s.camera.height = 24;
    return s;
}

test::MeanError furnace_mean(const Scene& s, int c, std::uint32_t integrator = CLP_INTEGRATOR_PATH) {
    RenderSettings st;
    st.integrator = integrator;
    st.max_depth = 64;
    st.seed = 5;
    RenderStats stats;
    const auto img = test::render(s, st, 64, &stats).linear;
    EXPECT_EQ(stats.nonfinite, 0u);
    return test::mean_error(test::channel(img, c));
}

const glm::vec3 kSky(0.9f, 0.6f, 0.3f);
// Three channels per check, alpha 1e-4 each.
const double kZ = 3.89;

}  // namespace

// Albedo-1 diffuse and mirror surfaces, and glass, return exactly the sky's
// radiance: every pixel's expectation is Le.
TEST(LightTransport, FurnaceConservesEnergy) {
    for (const SceneMaterial& m : {diffuse(glm::vec3(1.0f)), mirror(glm::vec3(1.0f)), dielectric(1.5f)}) {
        SCOPED_TRACE("material kind " + std::to_string(m.kind));
        for (auto integrator : test::kLightTransportIntegrators)
            test::expect_sky_furnace(sky_furnace(m, kSky, false), 1.0, integrator, 5);
    }
}

// Seen from inside, glass shows the sky n^2 times brighter: radiance is
// compressed into the denser medium (the 1/eta^2 of each refraction).
TEST(LightTransport, GlassSeenFromInside) {
    const float ior = 1.5f;
    test::expect_sky_furnace(sky_furnace(dielectric(ior), kSky, true), ior * ior, CLP_INTEGRATOR_PATH, 5);
}

// A GGX conductor with F0 = 1 never returns more than it receives, and rough
// ones visibly less (single scattering only).
TEST(LightTransport, GgxNeverCreatesEnergy) {
    const Scene s = sky_furnace(conductor(glm::vec3(1.0f), 0.8f), kSky, false);
    for (int c = 0; c < 3; ++c) {
        const auto e = furnace_mean(s, c);
        EXPECT_LE(e.mean, kSky[c] + kZ * e.std_error);
        EXPECT_LT(e.mean, kSky[c] * 0.99);
    }
}

namespace {
// A large diffuse floor (y = 0) seen through a narrow camera aimed at `at`,
// so every sample lands within a hair of that point.
Scene floor_scene(glm::vec3 albedo, glm::vec3 at) {
    Scene s;
    s.name = "floor";
    const auto id = s.add_material("floor", diffuse(albedo));
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {100, 1, 100})), id);
    s.camera.eye = at + glm::vec3(0, 2, -1);
    s.camera.target = at;
    s.camera.vfov_degrees = 0.01f;
    s.camera.width = s.camera.height = 8;
    return s;
}
}  // namespace

// Delta lights against the rendering equation in closed form: a Lambertian
// floor of albedo rho lit by intensity I from distance r at incidence theta
// has radiance rho/pi I cos(theta) / r^2 (directional: rho/pi E cos(theta)).
TEST(LightTransport, DeltaLightsMatchClosedForm) {
    const glm::vec3 at(0.3f, 0, 0.2f), rho(0.5f, 0.7f, 0.9f);
    struct Case {
        PunctualLight light;
        double cos_theta, r2;
    };
    PunctualLight point;
    point.position = {1.3f, 2.0f, 0.2f};
    point.intensity = glm::vec3(3.0f);
    PunctualLight spot = point;
    spot.type = PunctualLight::Type::Spot;
    spot.direction = at - spot.position;
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(-1, -2, 0.5f));
    sun.intensity = glm::vec3(2.0f);
    const glm::vec3 to_point = point.position - at;
    const double cos_p = to_point.y / glm::length(to_point), r2 = glm::dot(to_point, to_point);
    for (const Case& k : {Case{point, cos_p, r2}, Case{spot, cos_p, r2}, Case{sun, -double(sun.direction.y), 1.0}}) {
        Scene s = floor_scene(rho, at);
        s.lights = {k.light};
        RenderSettings st;
        st.max_depth = 1;  // direct light only: the floor sees nothing else
        const auto img = test::render(s, st, 4).linear;
        for (int c = 0; c < 3; ++c) {
            const double expected = rho[c] / kPi * k.light.intensity[c] * k.cos_theta / k.r2;
            const auto m = test::mean_error(test::channel(img, c));
            // The 0.01-degree view spreads the points by ~3e-4 of the distance: the
            // radiance varies by less than that relative amount; rounding far less.
            EXPECT_NEAR(m.mean, expected, 1e-3 * expected) << "light type " << int(k.light.type) << " channel " << c;
        }
    }
}

// Ambient occlusion: an open plane is exactly 1; next to a wall at distance x,
// with rays of length D, the occluded share of the cosine-weighted hemisphere
// is the disk segment of test::ao_next_to_wall.
TEST(LightTransport, AmbientOcclusionOpenPlaneAndCorner) {
    RenderSettings st;
    st.integrator = CLP_INTEGRATOR_AO;
    st.ao_distance = 1.0f;
    {
        const auto img = test::render(floor_scene(glm::vec3(0.5f), {0, 0, 0}), st, 16).linear;
        for (float v : img.rgb) ASSERT_EQ(v, 1.0f);
    }
    const double x = 0.25, D = 1.0;
    Scene s;
    s.name = "corner";
    test::add_floor_and_wall(s, s.add_material("grey", diffuse(glm::vec3(0.5f))));
    // Narrow, from the open side (so the wall does not block the view): every
    // sample lands within a hair of (x, 0, 0).
    s.camera.eye = glm::vec3(float(x) + 2, 2, 0);
    s.camera.target = {float(x), 0, 0};
    s.camera.vfov_degrees = 0.01f;
    s.camera.width = s.camera.height = 8;
    const auto img = test::render(s, st, 256).linear;
    const double expected = test::ao_next_to_wall(x, D);
    const auto m = test::mean_error(test::channel(img, 0));
    EXPECT_NEAR(m.mean, expected, 4.4 * m.std_error + 1e-4) << "closed form " << expected;
}

namespace {
// The thesis box with a glossy box, a glass ball, a rough glass box and a
// mirror ball added: every kind of path the integrators treat differently.
Scene mixed_cornell() {
    Scene s = cornell_thesis_scene();
    const auto glossy = s.add_material("test-glossy", conductor(glm::vec3(0.9f, 0.8f, 0.6f), 0.4f));
    const auto glass = s.add_material("test-glass", dielectric(1.5f));
    const auto chrome = s.add_material("test-mirror", mirror(glm::vec3(0.9f)));
    const auto frosted = s.add_material("test-rough-glass", dielectric(1.5f, 0.3f));
    s.add_triangles(transformed(make_box(), shape_transform({-0.3f, 0.45f, 0.1f}, {0.3f, 0.5f, 0}, glm::vec3(0.1f))),
                    frosted);
    s.add_triangles(transformed(make_icosphere(2), shape_transform({-0.25f, 0.0f, -0.25f}, {0, 0, 0}, glm::vec3(0.1f))),
                    glass);
    s.add_triangles(transformed(make_box(), shape_transform({0.25f, 0.0f, -0.3f}, {0, 0.4f, 0}, glm::vec3(0.12f))),
                    glossy);
    s.add_triangles(transformed(make_icosphere(1), shape_transform({0.0f, 0.6f, 0.2f}, {0, 0, 0}, glm::vec3(0.08f))),
                    chrome);
    s.camera.width = 40;
    s.camera.height = 32;
    return s;
}
}  // namespace

// Next-event estimation with MIS and BSDF sampling alone estimate the same
// image: equal in distribution, block by block.
TEST(LightTransport, NeeAndBsdfSamplingAgree) {
    const Scene s = mixed_cornell();
    RenderSettings st;
    st.max_depth = 6;
    st.integrator = CLP_INTEGRATOR_PATH;
    const auto a = runs(s, st, 32, 4, 100);
    st.integrator = CLP_INTEGRATOR_PATH_BSDF;
    const auto b = runs(s, st, 64, 4, 200);
    const auto r = test::image_agreement(a, b);
    EXPECT_TRUE(r.ok()) << r.describe();
}

// The same test must see a real difference: one bounce less is another image.
TEST(LightTransport, AgreementTestDetectsMissingBounce) {
    const Scene s = mixed_cornell();
    RenderSettings st;
    st.max_depth = 3;
    const auto a = runs(s, st, 16, 4, 300);
    st.max_depth = 2;
    const auto b = runs(s, st, 16, 4, 400);
    EXPECT_FALSE(test::image_agreement(a, b).ok());
}

// Kernels specialised to the scene and kernels with every feature compiled in
// give the same image in distribution.
TEST(LightTransport, SpecialisedAndAllFeatureKernelsAgree) {
    const Scene s = mixed_cornell();
    RenderSettings st;
    st.max_depth = 6;
    const auto a = runs(s, st, 16, 4, 500);
    st.all_features = true;
    const auto b = runs(s, st, 16, 4, 600);
    const auto r = test::image_agreement(a, b);
    EXPECT_TRUE(r.ok()) << r.describe();
}

namespace {
// A small equirectangular sky with a bright sun and a gradient, as PFM.
std::string write_sky(const std::string& name) {
    Image img;
    img.width = 32;
    img.height = 16;
    img.rgb.resize(32 * 16 * 3);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = 0.2f + 0.4f * float(16 - y) / 16 * (c == 2 ? 1.0f : 0.6f);
                if (x == 20 && y == 4) v = 400.0f;  // the sun: most of the power in one texel
                img.rgb[(y * 32 + x) * 3 + c] = v;
            }
    const std::string path = test::temp_path(name);
    write_pfm(path, img);
    return path;
}
}  // namespace

// Importance sampling the environment changes the noise, not the image.
TEST(LightTransport, EnvironmentImportanceSamplingAgreesWithUniform) {
    Scene s;
    s.name = "sky";
    const auto ground = s.add_material("ground", diffuse(glm::vec3(0.6f)));
    const auto ball = s.add_material("ball", conductor(glm::vec3(0.9f), 0.5f));
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {10, 1, 10})), ground);
    s.add_triangles(transformed(make_icosphere(2), shape_transform({0, 0.5f, 0}, {0, 0, 0}, glm::vec3(0.5f))), ball);
    s.environment.image = write_sky("test-sky.pfm");
    s.environment.rotation_degrees = 30;
    s.camera.eye = {0, 1.2f, -3};
    s.camera.target = {0, 0.4f, 0};
    s.camera.width = 32;
    s.camera.height = 24;
    RenderSettings st;
    st.max_depth = 4;
    const auto a = runs(s, st, 32, 4, 700);
    s.environment.importance_sampled = false;
    const auto b = runs(s, st, 128, 4, 800);
    const auto r = test::image_agreement(a, b);
    EXPECT_TRUE(r.ok()) << r.describe();
    std::filesystem::remove(s.environment.image);
}

namespace {
// A bundled CC0 HDRI (scenes/hdri/studio.exr, 1024x512 float OpenEXR) lighting
// the ground-and-ball scene above.
Scene studio_scene(float rotation_degrees) {
    Scene s;
    s.name = "studio";
    const auto ground = s.add_material("ground", diffuse(glm::vec3(0.6f)));
    const auto ball = s.add_material("ball", conductor(glm::vec3(0.9f), 0.5f));
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {10, 1, 10})), ground);
    s.add_triangles(transformed(make_icosphere(2), shape_transform({0, 0.5f, 0}, {0, 0, 0}, glm::vec3(0.5f))), ball);
    s.environment.image = (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "scenes" / "hdri" / "studio.exr")
                              .lexically_normal()
                              .string();
    s.environment.rotation_degrees = rotation_degrees;
    s.camera.eye = {0, 1.2f, -3};
    s.camera.target = {0, 0.4f, 0};
    s.camera.width = 32;
    s.camera.height = 24;
    return s;
}
}  // namespace

// An EXR environment is importance-sampled like any other image: the same
// image either way. Control: the map turned by another 90 degrees differs.
TEST(LightTransport, ExrEnvironmentImportanceSamplingAgreesWithUniform) {
    Scene s = studio_scene(30);
    RenderSettings st;
    st.max_depth = 4;
    const auto a = runs(s, st, 32, 4, 900);
    s.environment.importance_sampled = false;
    const auto b = runs(s, st, 128, 4, 1000);
    const auto r = test::image_agreement(a, b);
    EXPECT_TRUE(r.ok()) << r.describe();
    Scene turned = studio_scene(120);
    const auto c = runs(turned, st, 32, 4, 1100);
    EXPECT_FALSE(test::image_agreement(c, b).ok()) << "control: the map turned by 90 degrees";
}

// Slightly negative texels (lossy EXR compression rings below zero: studio.exr
// has -3e-6) read as black; a NaN is refused, naming the pixel.
TEST(LightTransport, EnvironmentNegativeTexelsAreBlackAndNanIsRefused) {
    Image img;
    img.width = 2;
    img.height = 1;
    img.rgb = {-0.001f, 0.5f, 1.0f, 2.0f, 2.0f, 2.0f};
    Environment env;
    env.image = test::temp_path("negative-sky.pfm");
    write_pfm(env.image, img);
    const EnvironmentMap m = load_environment_map(env);
    EXPECT_EQ(m.negative_values, 1u);
    EXPECT_EQ(m.pixels[0], 0.0f);
    EXPECT_EQ(m.pixels[1], 0.5f);
    img.rgb[4] = NAN;
    write_pfm(env.image, img);
    try {
        load_environment_map(env);
        ADD_FAILURE() << "a NaN texel was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("pixel (1, 0) is not finite"), std::string::npos) << e.what();
    }
    std::filesystem::remove(env.image);
}

#ifdef CLPATH_WITH_OIIO
namespace {
// Writes float channels as an OpenEXR file (float, not half: exact values).
void write_float_exr(const std::string& path, int w, int h, int channels, const std::vector<float>& v) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    const OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, v.data())) << out->geterror();
    out->close();
}
}  // namespace

// An EXR environment builds the same map and distribution, bit for bit, as
// the same floats in a PFM; a one-channel EXR is grey.
TEST(LightTransport, ExrEnvironmentIsTheSameMapAsThePfm) {
    Environment pfm, exr, grey;
    pfm.image = write_sky("same-sky.pfm");
    const Image img = read_image(pfm.image);
    exr.image = test::temp_path("same-sky.exr");
    write_float_exr(exr.image, img.width, img.height, 3, img.rgb);
    const EnvironmentMap a = load_environment_map(pfm), b = load_environment_map(exr);
    EXPECT_EQ(a.width, 32);
    EXPECT_EQ(b.pixels, a.pixels);
    EXPECT_EQ(b.cdf, a.cdf);
    std::vector<float> g(img.rgb.size() / 3);
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = img.rgb[3 * i + 1];
    grey.image = test::temp_path("grey-sky.exr");
    write_float_exr(grey.image, img.width, img.height, 1, g);
    const EnvironmentMap c = load_environment_map(grey);
    for (std::size_t i = 0; i < g.size(); ++i)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(c.pixels[4 * i + std::size_t(k)], g[i]) << "texel " << i;
    for (const auto& f : {pfm.image, exr.image, grey.image}) std::filesystem::remove(f);
}
#endif
