// The light sampler choice (render/settings.hpp LightSampler): when Auto takes
// the light BVH, and that picking lights by it (kernels/light_bvh.cl through
// path.cl) leaves every image's expectation as picking by power does: both
// are rendered with independent seeds and compared block by block
// (test::image_agreement at a false-failure rate of 1e-7). Controls: the same
// comparison rejects the light BVH's renders when next-event estimation
// divides by twice the pick's pmf, and, in the room, when the MIS weight of a
// BSDF sample that hits a light takes the power pmf instead of the light BVH's. (A pmf taken
// without the normal, or halved, in the MIS weight alone biases these images
// by less than the test resolves at this size: the lamp is rarely found by
// BSDF sampling where its light-sampling pdf is not far larger.)
#include <gtest/gtest.h>

#include <string>

#include "cl/embedded_sources.hpp"
#include "render/kernel_features.hpp"
#include "render/prepared_scene.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/image_agreement.hpp"
#include "support/repo_root.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

Scene scene_file(const std::string& rel, int width, int height) {
    Scene s = load_scene((test::repo_root() / rel).string());
    s.camera.width = width;
    s.camera.height = height;
    return s;
}

RenderSettings sampler(LightSampler l, std::uint32_t max_depth = 6) {
    RenderSettings s;
    s.light_sampler = l;
    s.max_depth = max_depth;
    return s;
}

TEST(LightSampler, AutoTakesTheLightBvhWhereManyLightsAreSpreadOut) {
    const SceneFeatures cornell = scene_features(scene_file("scenes/cornell-classic.json", 8, 8));
    const Scene room_scene = scene_file("scenes/room-lamp-sky.json", 8, 8);
    const SceneFeatures room = scene_features(room_scene);
    const SceneFeatures glass = scene_features(scene_file("scenes/hard/glass-in-glass.json", 8, 8));
    const SceneFeatures city = scene_features(night_city_scene(8));  // 16 emissive triangles
    const SceneFeatures one_lamp = scene_features(night_city_scene(7));
    EXPECT_FALSE(cornell.many_lights);  // one quad lamp
    EXPECT_FALSE(room.many_lights);     // one lamp beside a sky: the scene file asks for the light BVH instead
    EXPECT_FALSE(glass.many_lights);    // 80 triangles of one small sphere
    EXPECT_TRUE(city.many_lights);
    EXPECT_FALSE(one_lamp.many_lights);  // 14 triangles, below kManyFiniteLights
    EXPECT_EQ(settings_from_scene(room_scene.render).light_sampler, LightSampler::Bvh);
    const RenderSettings autos = sampler(LightSampler::Auto);
    EXPECT_FALSE(uses_light_bvh(cornell, autos));
    EXPECT_TRUE(uses_light_bvh(city, autos));
    EXPECT_TRUE(uses_light_bvh(cornell, sampler(LightSampler::Bvh)));
    EXPECT_FALSE(uses_light_bvh(room, sampler(LightSampler::Power)));
    RenderSettings ao = sampler(LightSampler::Bvh);
    ao.integrator = CLP_INTEGRATOR_AO;  // no light sampling at all
    EXPECT_FALSE(uses_light_bvh(room, ao));
    EXPECT_NE(build_options(kernel_features(city, autos)).find(" -DCLP_LIGHT_BVH"), std::string::npos);
    EXPECT_EQ(build_options(kernel_features(cornell, autos)).find("CLP_LIGHT_BVH"), std::string::npos);
    // A choice of estimator: --all-features compiles it in only where it is chosen.
    RenderSettings all = autos;
    all.all_features = true;
    EXPECT_FALSE(kernel_features(cornell, all).light_bvh);
    EXPECT_TRUE(kernel_features(city, all).light_bvh);
    try {
        parse_light_sampler("tree");
        FAIL() << "an unknown sampler was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("auto, power, bvh"), std::string::npos) << e.what();
    }
}

TEST(LightSampler, AScenePreparedForPowerAloneHasNoLightBvhAndSaysSo) {
    const Scene room = scene_file("scenes/room-lamp-sky.json", 8, 6);
    const auto power = prepare_scene(room, sampler(LightSampler::Power));
    EXPECT_FALSE(power->summary.light_bvh.built);
    // Auto keeps power for one lamp beside a sky: no tree to upload either.
    EXPECT_FALSE(prepare_scene(room, sampler(LightSampler::Auto))->summary.light_bvh.built);
    const auto bvh = prepare_scene(room, sampler(LightSampler::Bvh));
    ASSERT_TRUE(bvh->summary.light_bvh.built);
    EXPECT_EQ(bvh->summary.light_bvh.infinite_count, 1u);  // the sky
    EXPECT_EQ(bvh->summary.light_bvh.node_count, 3u);      // the lamp's two triangles under one root
    try {
        Renderer r(test::device(), *power, sampler(LightSampler::Bvh));
        r.add_samples(1);
        FAIL() << "rendered with a light BVH the scene was not prepared with";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("without its light BVH"), std::string::npos) << e.what();
    }
}

std::vector<Image> runs(const PreparedScene& scene, const RenderSettings& st, std::uint32_t spp, int k,
                        std::uint32_t seed0, const KernelVariant& variant = {}) {
    Renderer r(test::device(), scene, st, variant);
    std::vector<Image> out;
    for (int i = 0; i < k; ++i) {
        RenderSettings s = st;
        s.seed = seed0 + std::uint32_t(i);
        r.set_settings(s);
        r.add_samples(spp);
        out.push_back(r.resolve().linear);
    }
    return out;
}

// path.cl with one expression replaced; fails the test when it is not there.
KernelVariant path_cl_with(const std::string& from, const std::string& to) {
    std::string text = embedded_source("path.cl");
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "path.cl no longer has: " << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return KernelVariant{{{"path.cl", text}}, ""};
}

// mis_control: the scene's lights are found by BSDF sampling often enough
// that the MIS control is resolved (the city's 25 cm lamps are not).
void expect_light_bvh_unbiased(const Scene& scene, std::uint32_t spp, int k, bool mis_control) {
    const auto prepared = prepare_scene(scene, sampler(LightSampler::Bvh));  // the alias table is always there
    const auto power = runs(*prepared, sampler(LightSampler::Power), spp, k, 100);
    const auto bvh = runs(*prepared, sampler(LightSampler::Bvh), spp, k, 200);
    const test::Agreement same = test::image_agreement(power, bvh, 8, 1e-7);
    EXPECT_TRUE(same.ok()) << scene.name << ": " << same.describe();
    // MIS weighs a BSDF sample that hits a light by the power pmf while NEE picks by the BVH.
    if (mis_control) {
        const auto power_mis = runs(*prepared, sampler(LightSampler::Bvh), spp, k, 200,
                                    path_cl_with("light_bvh_pmf(&sc->lbvh, ps->prev_p, lbvh_octahedral(ps->prev_n), li, is_infinite)",
                                                 "sc->alias[li].pmf"));
        const test::Agreement wrong_mis = test::image_agreement(power, power_mis, 8, 1e-7);
        EXPECT_FALSE(wrong_mis.ok()) << scene.name << ", MIS by the power pmf: " << wrong_mis.describe();
    }
    // NEE divides by a pmf twice the pick's.
    const auto doubled = runs(*prepared, sampler(LightSampler::Bvh), spp, k, 200,
                              path_cl_with("if (li == CLP_NO_LIGHT) return 0;", "if (li == CLP_NO_LIGHT) return 0;\n    pmf *= 2.0f;"));
    const test::Agreement wrong_pick = test::image_agreement(power, doubled, 8, 1e-7);
    EXPECT_FALSE(wrong_pick.ok()) << scene.name << ", NEE's pmf doubled: " << wrong_pick.describe();
}

TEST(LightSampler, TheLightBvhChangesNoExpectationUnderTheSky) {
    expect_light_bvh_unbiased(scene_file("scenes/room-lamp-sky.json", 48, 36), 64, 8, true);
}

TEST(LightSampler, TheLightBvhChangesNoExpectationAmongManyLamps) {
    Scene city = night_city_scene(300);
    city.camera.width = 48;
    city.camera.height = 32;
    expect_light_bvh_unbiased(city, 64, 8, false);
}

}  // namespace
