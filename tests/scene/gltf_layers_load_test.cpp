// The glTF layers the loader reads (host/scene/load/gltf_materials.cpp):
// KHR_materials_clearcoat and KHR_materials_transmission, their defaults,
// textures and bad values, and the kernel features they switch on.
#include <gtest/gtest.h>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "render/kernel_features.hpp"
#include "scene/load/gltf_scene.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {

LoadOptions options(MemoryFiles& f) {
    LoadOptions o = f.options();
    o.decode_texture = fake_rgba_decode;
    o.presentation.ground = false;
    return o;
}

// The quad with one material carrying these extensions, and two 1x1 images
// (textures 0 and 1).
std::string quad_with(const json& extensions) {
    GltfBuilder g = quad_model();
    g.doc["materials"] = {{{"name", "layered"}, {"extensions", extensions}}};
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const std::string texel = std::string("RGBA\x01\x01", 6) + std::string("\x80\x40\x20\xff", 4);
    g.doc["images"] = {{{"uri", "data:image/png;base64," + base64(texel)}},
                       {{"uri", "data:image/png;base64," + base64(texel + "")}}};
    g.doc["samplers"] = {{{"wrapS", 33071}}};
    g.doc["textures"] = {{{"source", 0}}, {{"source", 1}, {"sampler", 0}}};
    return g.embedded();
}

Scene load(const json& extensions) {
    MemoryFiles f;
    f.files["l.gltf"] = quad_with(extensions);
    return gltf_scene("l.gltf", options(f));
}

std::string error(const json& extensions) {
    MemoryFiles f;
    f.files["l.gltf"] = quad_with(extensions);
    return error_of([&] { (void)gltf_scene("l.gltf", options(f)); });
}

const SceneMaterial& material(const Scene& s) { return s.materials[s.triangle_material[0]]; }

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(GltfLayersLoad, DefaultsWithoutTheExtensions) {
    const Scene s = load(json::object());
    const SceneMaterial& m = material(s);
    EXPECT_EQ(m.clearcoat, 0.0f);
    EXPECT_EQ(m.clearcoat_roughness, 0.0f);
    EXPECT_EQ(m.clearcoat_normal_scale, 1.0f);
    EXPECT_EQ(m.transmission, 0.0f);
    for (unsigned t = CLP_TEX_CORE_SLOTS; t < CLP_TEX_SLOTS; ++t) EXPECT_EQ(m.texture[t], CLP_NO_TEXTURE) << t;
    const SceneFeatures f = scene_features(s);
    EXPECT_FALSE(f.clearcoat);
    EXPECT_FALSE(f.transmission);
    EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfLayersLoad, ExtensionDefaultsAreTheSpecifications) {
    // An empty clearcoat object: factor 0 (no coat), roughness 0; transmission 0.
    const Scene s = load({{"KHR_materials_clearcoat", json::object()}, {"KHR_materials_transmission", json::object()}});
    const SceneMaterial& m = material(s);
    EXPECT_EQ(m.clearcoat, 0.0f);
    EXPECT_EQ(m.clearcoat_roughness, 0.0f);
    EXPECT_EQ(m.transmission, 0.0f);
    const SceneFeatures f = scene_features(s);
    EXPECT_FALSE(f.clearcoat) << "a coat of weight 0 costs nothing";
    EXPECT_FALSE(f.transmission);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(GltfLayersLoad, FactorsAndTextures) {
    const Scene s = load({{"KHR_materials_clearcoat",
                           {{"clearcoatFactor", 0.75},
                            {"clearcoatTexture", {{"index", 0}}},
                            {"clearcoatRoughnessFactor", 0.25},
                            {"clearcoatRoughnessTexture", {{"index", 1}}},
                            {"clearcoatNormalTexture", {{"index", 1}, {"scale", 0.5}}}}},
                          {"KHR_materials_transmission", {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}}}}}});
    const SceneMaterial& m = material(s);
    EXPECT_FLOAT_EQ(m.clearcoat, 0.75f);
    EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.25f);
    EXPECT_FLOAT_EQ(m.clearcoat_normal_scale, 0.5f);
    EXPECT_FLOAT_EQ(m.transmission, 0.9f);
    // Two images, the second with its own sampler: two textures, each loaded once.
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(m.texture[CLP_TEX_CLEARCOAT], 0);
    EXPECT_EQ(m.texture[CLP_TEX_CLEARCOAT_ROUGHNESS], 1);
    EXPECT_EQ(m.texture[CLP_TEX_CLEARCOAT_NORMAL], 1);
    EXPECT_EQ(m.texture[CLP_TEX_TRANSMISSION], 0);
    EXPECT_EQ(s.textures[1].wrap_s, CLP_WRAP_CLAMP);
    const SceneFeatures f = scene_features(s);
    EXPECT_TRUE(f.clearcoat);
    EXPECT_TRUE(f.transmission);
    EXPECT_TRUE(f.textures);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    // The kernels get the features, and no program without them does.
    const std::string o = build_options(kernel_features(f, RenderSettings{}));
    EXPECT_TRUE(has(o, "-DCLP_HAS_CLEARCOAT")) << o;
    EXPECT_TRUE(has(o, "-DCLP_HAS_TRANSMISSION")) << o;
    RenderSettings all;
    all.all_features = true;
    const std::string plain = build_options(kernel_features(SceneFeatures{}, all));
    EXPECT_FALSE(has(plain, "CLEARCOAT") || has(plain, "TRANSMISSION")) << "every feature but the layers: " << plain;
}

TEST(GltfLayersLoad, ClearcoatAloneSwitchesOnlyTheCoat) {
    const Scene s = load({{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}});
    const SceneFeatures f = scene_features(s);
    EXPECT_TRUE(f.clearcoat);
    EXPECT_FALSE(f.transmission);
    EXPECT_FALSE(f.textures);
}

TEST(GltfLayersLoad, MapsOfAZeroLayerAreDropped) {
    // The spec multiplies a map by its factor: at 0 the map changes nothing, and is not loaded.
    const Scene s = load({{"KHR_materials_clearcoat", {{"clearcoatTexture", {{"index", 0}}}}},
                          {"KHR_materials_transmission", {{"transmissionTexture", {{"index", 1}}}}}});
    const SceneMaterial& m = material(s);
    for (unsigned t = CLP_TEX_CORE_SLOTS; t < CLP_TEX_SLOTS; ++t) EXPECT_EQ(m.texture[t], CLP_NO_TEXTURE) << t;
    EXPECT_FALSE(scene_features(s).textures);
}

TEST(GltfLayersLoad, BadValuesNameTheirField) {
    struct Case {
        json ext;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {{{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}},
         "l.gltf: materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: must be in [0"},
        {{{"KHR_materials_clearcoat", {{"clearcoatFactor", 1}, {"clearcoatRoughnessFactor", -0.1}}}},
         "materials[0].extensions.KHR_materials_clearcoat.clearcoatRoughnessFactor: must be in [0"},
        {{{"KHR_materials_clearcoat", {{"clearcoatFactor", "much"}}}},
         "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: must be a number"},
        {{{"KHR_materials_transmission", {{"transmissionFactor", 2}}}},
         "materials[0].extensions.KHR_materials_transmission.transmissionFactor: must be in [0"},
        {{{"KHR_materials_transmission", {{"transmissionFactor", 1}, {"transmissionTexture", {{"index", 9}}}}}},
         "materials[0].extensions.KHR_materials_transmission.transmissionTexture.index: texture 9 does not exist"},
        {{{"KHR_materials_clearcoat", {{"clearcoatFactor", 1}, {"clearcoatTexture", {{"texCoord", 0}}}}}},
         "materials[0].extensions.KHR_materials_clearcoat.clearcoatTexture: must be a texture reference"},
    };
    for (const Case& c : cases) {
        const std::string e = error(c.ext);
        EXPECT_TRUE(has(e, c.expect)) << c.ext.dump() << ": " << e;
    }
}

TEST(GltfLayersLoad, VolumeIsNamedAsThinWalled) {
    const Scene s = load({{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                          {"KHR_materials_volume", {{"thicknessFactor", 0.1}}}});
    EXPECT_FLOAT_EQ(material(s).transmission, 1.0f);
    bool named = false;
    for (const auto& w : s.warnings) named = named || has(w, "thin-walled");
    EXPECT_TRUE(named);
}

TEST(GltfLayersLoad, RequiredLayersLoadWithoutWarnings) {
    GltfBuilder g = quad_model();
    g.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_transmission"};
    g.doc["extensionsRequired"] = {"KHR_materials_clearcoat", "KHR_materials_transmission"};
    const Scene s = gltf_text_scene("r.gltf", g.embedded());
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}
