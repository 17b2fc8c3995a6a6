// The default presentation of a bare mesh: the view shows the mesh's largest
// faces, and a rendered bare mesh shows the model, the ground and the model's
// shadow on it. A bare glTF model gets the same, less what the file brings
// (its camera, its lights or emitters).
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "render/settings.hpp"
#include "scene/gltf_files.hpp"
#include "scene/load/gltf_scene.hpp"
#include "scene/memory_files.hpp"
#include "scene/load/presentation.hpp"
#include "scene/load/scene_file.hpp"
#include "support/render_helpers.hpp"

namespace clpath {
namespace {

Scene bare(const std::string& obj, const PresentationOptions& p = {}) {
    test::MemoryFiles files;
    files.files["m/model.obj"] = obj;
    LoadOptions o = files.options();
    o.presentation = p;
    return obj_scene("m/model.obj", o);
}

// A plate in the YZ plane facing +x, and one in the XY plane facing +z.
const char* kYzPlate = "v 0 0 -1\nv 0 0 1\nv 0 1.2 1\nv 0 1.2 -1\nf 1 4 3 2\n";
const char* kXyPlate = "v -1 0 0\nv 1 0 0\nv 1 1.2 0\nv -1 1.2 0\nf 1 2 3 4\n";
// A unit cube standing on y = 0, faces outward.
const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\nf 1 2 6 5\n";

// The cube above as a glTF model: unindexed triangles of a terracotta
// dielectric whose red albedo (0.8) is the OBJ cube's, for the pixel
// classification below. (Grey, its specular coat brings its mean luminance
// to within 5 % of the lit ground's, and "stands out" below would not hold.)
test::GltfBuilder gltf_cube() {
    const float v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 5, 8, 4}, {2, 3, 7, 6}, {4, 8, 7, 3}, {1, 2, 6, 5}};
    std::vector<float> pos;
    for (const auto& f : faces)
        for (int k : {0, 1, 2, 0, 2, 3}) pos.insert(pos.end(), v[f[k] - 1], v[f[k] - 1] + 3);
    test::GltfBuilder g;
    const int p = g.floats(pos, "VEC3", 3);
    using nlohmann::json;
    g.doc["materials"] = json::array({json{{"pbrMetallicRoughness",
                                            {{"baseColorFactor", {0.8, 0.45, 0.3, 1}}, {"metallicFactor", 0}}}}});
    json prim = {{"attributes", {{"POSITION", p}}}, {"material", 0}};
    g.doc["meshes"] = json::array({json{{"primitives", json::array({prim})}}});
    g.doc["nodes"] = json::array({json{{"mesh", 0}}});
    return g;
}

Scene bare_gltf(const test::GltfBuilder& g, const PresentationOptions& p = {}, const std::string& camera = "") {
    test::MemoryFiles files;
    files.files["m/model.gltf"] = g.embedded();
    LoadOptions o = files.options();
    o.presentation = p;
    o.gltf_camera = camera;
    return gltf_scene("m/model.gltf", o);
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Presentation, FlatModelsAreSeenFaceOn) {
    // The direction is chosen from the mesh alone (before the ground is added).
    PresentationOptions mesh_only;
    mesh_only.ground = false;
    const glm::vec3 yz = presentation_view_direction(bare(kYzPlate, mesh_only));
    EXPECT_GT(yz.x, 0.9f) << "the YZ plate faces +x and must be seen from +x";
    const glm::vec3 xy = presentation_view_direction(bare(kXyPlate, mesh_only));
    EXPECT_GT(xy.z, 0.9f);
    // The camera placed by the presentation looks along the same direction.
    const Scene placed = bare(kYzPlate);
    EXPECT_GT(glm::normalize(placed.camera.eye - placed.camera.target).x, 0.9f);
    // A cube shows three faces: a three-quarter view, from above.
    const glm::vec3 cube = presentation_view_direction(bare(kCube, mesh_only));
    EXPECT_GT(std::abs(cube.x), 0.3f);
    EXPECT_GT(cube.y, 0.3f);
    EXPECT_GT(std::abs(cube.z), 0.3f);
}

// One face of the cube listed again and again (assimp's box_longline.obj
// writes it as one polygon going round its four corners 35 times): still
// the three-quarter view, not face-on to the repeated face.
TEST(Presentation, RepeatedFacesCountOnce) {
    PresentationOptions mesh_only;
    mesh_only.ground = false;
    std::string copies = kCube, polygon = std::string(kCube) + "f";
    for (int i = 0; i < 40; ++i) copies += "f 5 6 7 8\n", polygon += " 5 6 7 8";
    for (const std::string& obj : {copies, polygon + "\n"}) {
        const Scene s = bare(obj, mesh_only);
        ASSERT_GE(s.triangle_count(), 12u);
        const glm::vec3 d = presentation_view_direction(s);
        EXPECT_GT(std::abs(d.x), 0.3f);
        EXPECT_GT(d.y, 0.3f);
        EXPECT_GT(d.z, 0.3f);  // the repeated face (+z) is in view
        const glm::vec3 cube = presentation_view_direction(bare(kCube, mesh_only));
        EXPECT_EQ(d, cube);
    }
}

TEST(Presentation, AddsCameraGroundSkyAndSun) {
    const Scene s = bare(kCube);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, PunctualLight::Type::Directional);
    EXPECT_LT(s.lights[0].direction.y, 0.0f);  // the sun shines down
    EXPECT_GT(s.environment.color.x, 0.0f);
    EXPECT_EQ(s.triangle_count(), 12u + 2u);  // the cube and the ground's two triangles
    EXPECT_EQ(s.material_names.back(), "(ground)");
    // Overrides: no ground; an environment that replaces sky and sun.
    PresentationOptions p;
    p.ground = false;
    p.environment = Environment{};
    p.environment->color = glm::vec3(0.5f);
    const Scene o = bare(kCube, p);
    EXPECT_EQ(o.triangle_count(), 12u);
    EXPECT_TRUE(o.lights.empty());
    EXPECT_EQ(o.environment.color, glm::vec3(0.5f));
}

// A glTF model with no camera and no lights is presented as the same OBJ is:
// the same camera, ground, sky and sun, and the same overrides.
TEST(Presentation, BareGltfGetsTheObjPresentation) {
    const Scene obj = bare(kCube), gltf = bare_gltf(gltf_cube());
    EXPECT_EQ(gltf.triangle_count(), 12u + 2u);  // the cube and the ground's two triangles
    EXPECT_EQ(gltf.material_names.back(), "(ground)");
    expect_near(gltf.camera.eye, obj.camera.eye);
    expect_near(gltf.camera.target, obj.camera.target);
    EXPECT_EQ(gltf.camera.vfov_degrees, obj.camera.vfov_degrees);
    ASSERT_EQ(gltf.lights.size(), 1u);
    EXPECT_EQ(gltf.lights[0].type, PunctualLight::Type::Directional);
    expect_near(gltf.lights[0].direction, obj.lights.at(0).direction);
    EXPECT_EQ(gltf.environment.color, obj.environment.color);
    PresentationOptions p;
    p.ground = false;
    p.environment = Environment{};
    p.environment->color = glm::vec3(0.5f);
    const Scene o = bare_gltf(gltf_cube(), p);
    EXPECT_EQ(o.triangle_count(), 12u);
    EXPECT_TRUE(o.lights.empty());
    EXPECT_EQ(o.environment.color, glm::vec3(0.5f));
}

// A file's camera is kept (--gltf-camera still picks it); the ground, sky and
// sun are added, the sun beside that camera's view.
TEST(Presentation, GltfCameraIsKept) {
    test::GltfBuilder g = gltf_cube();
    g.doc["cameras"] = nlohmann::json::array({nlohmann::json{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}},
                                              nlohmann::json{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
    g.doc["nodes"].push_back({{"camera", 0}, {"translation", {0.5, 0.5, 6}}});
    g.doc["nodes"].push_back({{"camera", 1}, {"translation", {0.5, 0.5, 9}}});
    for (const std::string pick : {"", "1"}) {
        const Scene s = bare_gltf(g, {}, pick);
        expect_near(s.camera.eye, {0.5f, 0.5f, pick.empty() ? 6.0f : 9.0f});
        expect_near(s.camera.target, {0.5f, 0.5f, pick.empty() ? 5.0f : 8.0f});
        EXPECT_EQ(s.triangle_count(), 12u + 2u);
        ASSERT_EQ(s.lights.size(), 1u);
        EXPECT_LT(s.lights[0].direction.y, 0.0f);
        // From the camera at +z the sun stands behind it, turned aside.
        EXPECT_LT(s.lights[0].direction.z, 0.0f);
        EXPECT_GT(std::abs(s.lights[0].direction.x), 0.1f);
    }
}

// Punctual lights and emitting materials strong enough to light the model
// are its own lighting: no sun and, as for an emitting OBJ, no ground unless
// --env replaces the lighting.
TEST(Presentation, GltfLightsOrEmittersReplaceSunAndGround) {
    const Scene obj = bare(kCube);
    test::GltfBuilder lit = gltf_cube();
    lit.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    // 50 W/sr from 2.6 m: about 7 W/m^2 at the cube, twice the sky and sun's.
    lit.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", nlohmann::json::array({nlohmann::json{{"type", "point"}, {"intensity", 50}}})}}}};
    lit.doc["nodes"].push_back({{"translation", {0.5, 3, 0.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    test::GltfBuilder glowing = gltf_cube();
    glowing.doc["materials"][0]["emissiveFactor"] = {1, 1, 1};
    for (const auto* g : {&lit, &glowing}) {
        const Scene s = bare_gltf(*g);
        const std::size_t file_lights = g == &lit ? 1 : 0;
        ASSERT_EQ(s.lights.size(), file_lights) << "no sun is added";
        if (file_lights) {
            EXPECT_EQ(s.lights[0].type, PunctualLight::Type::Point);
        }
        EXPECT_EQ(s.triangle_count(), 12u) << "no ground";
        EXPECT_FALSE(s.environment.emits()) << "no sky";
        expect_near(s.camera.eye, obj.camera.eye);  // still framed
        ASSERT_EQ(s.notes.size(), 1u);
        EXPECT_NE(s.notes[0].find("own lights and emitters light it"), std::string::npos) << s.notes[0];
        PresentationOptions p;
        p.environment = Environment{};
        p.environment->color = glm::vec3(0.25f);
        const Scene e = bare_gltf(*g, p);
        EXPECT_EQ(e.triangle_count(), 12u + 2u) << "--env: the ground is added";
        EXPECT_EQ(e.lights.size(), file_lights);
        EXPECT_EQ(e.environment.color, glm::vec3(0.25f));
    }
}

// The cube with one emitting material whose emission texture is black but
// for one texel; `lit_triangles` of its triangles sample that texel.
Scene cube_with_emission_texture(std::size_t lit_triangles) {
    PresentationOptions none;
    none.ground = false;
    Scene s = bare(kCube, none);  // the cube alone, then stripped of the presentation's lighting
    s.lights.clear();
    s.environment = Environment{};
    s.notes.clear();
    SceneMaterial m = s.materials.at(0);
    m.emission[0] = m.emission[1] = m.emission[2] = 1;  // emissiveFactor 1, as the Damaged Helmet's
    Texture t;
    t.name = "display";
    t.width = 2;
    t.height = 1;
    t.rgba8 = {0, 0, 0, 255, 255, 255, 255, 255};
    s.textures = {t};
    m.texture[CLP_TEX_EMISSION] = 0;
    for (auto& mm : s.materials) mm = m;
    s.uvs.assign(s.vertices.size(), glm::vec2(0.25f, 0.5f));  // the black texel
    for (std::size_t t = 0; t < lit_triangles; ++t)
        for (int k = 0; k < 3; ++k) s.uvs[3 * t + k] = glm::vec2(0.75f, 0.5f);
    return s;
}

// The Damaged Helmet's case: every material "emits" (a factor of 1), but its
// texture is black save a small display. The presentation weighs the light
// the emitters really give and adds the sky, the sun and the ground; the
// control, the whole texture lit, keeps the model's own lighting.
TEST(Presentation, WeakEmittersGetSkySunAndGround) {
    Scene weak = cube_with_emission_texture(1);
    present_model(weak, {}, false);
    ASSERT_EQ(weak.lights.size(), 1u) << "the sun is added";
    EXPECT_TRUE(weak.environment.emits()) << "the sky is added";
    EXPECT_EQ(weak.triangle_count(), 12u + 2u) << "the ground is added";
    ASSERT_EQ(weak.notes.size(), 1u);
    EXPECT_NE(weak.notes[0].find("are added beside them"), std::string::npos) << weak.notes[0];
    EXPECT_TRUE(emits(weak.materials[0])) << "the display still shines";

    Scene strong = cube_with_emission_texture(12);
    present_model(strong, {}, false);
    EXPECT_TRUE(strong.lights.empty());
    EXPECT_FALSE(strong.environment.emits());
    EXPECT_EQ(strong.triangle_count(), 12u);
    ASSERT_EQ(strong.notes.size(), 1u);
    EXPECT_NE(strong.notes[0].find("light it"), std::string::npos) << strong.notes[0];
}

// A weak point light (a tenth of the threshold) is kept, with the sky and sun beside it.
TEST(Presentation, WeakPunctualLightGetsSkySunAndGround) {
    PresentationOptions none;
    none.ground = false;
    Scene s = bare(kCube, none);
    s.lights.clear();
    s.environment = Environment{};
    s.notes.clear();
    PunctualLight l;
    l.position = glm::vec3(0.5f, 3, 0.5f);
    const float d2 = glm::dot(l.position - glm::vec3(0.5f), l.position - glm::vec3(0.5f));
    l.intensity = glm::vec3(0.1f * presentation::kOwnLightEnough * presentation_irradiance() * d2);
    s.lights.push_back(l);
    present_model(s, {}, false);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[1].type, PunctualLight::Type::Directional);
    EXPECT_TRUE(s.environment.emits());
}

// The default view is never steeper than kMaxElevation, and the model's
// bounding sphere fills the frame's height up to kFramingMargin.
TEST(Presentation, FramesTheBoundingSphereFromAShallowView) {
    for (const char* obj : {kCube, kYzPlate, kXyPlate}) {
        const Scene s = bare(obj);
        const glm::vec3 view = s.camera.target - s.camera.eye;
        const float elevation = glm::degrees(std::asin(-view.y / glm::length(view)));
        EXPECT_LE(elevation, presentation::kMaxElevation + 1e-3f);
        EXPECT_GE(elevation, 0.0f);
        float r = 0;
        for (std::size_t i = 0; i < 3 * (s.triangle_count() - 2); ++i)  // the model's, not the ground's
            r = std::max(r, glm::length(s.vertices[i] - s.camera.target));
        const float half_angle = std::asin(r / glm::length(view));
        const float half_fov = std::atan(std::tan(glm::radians(s.camera.vfov_degrees) / 2));
        EXPECT_NEAR(std::tan(half_angle) / std::tan(half_fov), presentation::kFramingMargin, 2e-3f) << obj;
    }
}

// Möller and Trumbore (1997) on the CPU: does the segment from o along d
// (unit) hit any triangle of the model (the first `model` triangles)?
bool blocked(const Scene& s, std::size_t model, glm::vec3 o, glm::vec3 d) {
    for (std::size_t t = 0; t < model; ++t) {
        const glm::vec3 a = s.vertices[3 * t], e1 = s.vertices[3 * t + 1] - a, e2 = s.vertices[3 * t + 2] - a;
        const glm::vec3 p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 q = o - a;
        const float u = glm::dot(q, p) / det;
        const glm::vec3 r = glm::cross(q, e1);
        const float v = glm::dot(d, r) / det, dist = glm::dot(e2, r) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && dist > 1e-4f) return true;
    }
    return false;
}

struct Regions {
    std::size_t model = 0, lit = 0, shadow = 0, pixels = 0;
    double model_mean = 0, lit_mean = 0, shadow_mean = 0;  // luminance of the path-traced image
};

// Classifies each pixel by its albedo (model 0.8, ground 0.5, sky 0); ground
// pixels are lit or in the model's shadow by a CPU shadow ray from the ground
// point under every corner and the centre of the pixel (all five must agree).
Regions regions(const Scene& s, std::size_t model_triangles, bool with_sun_for_shadow_ray, glm::vec3 sun_dir) {
    RenderSettings albedo = settings_from_scene(s.render);
    albedo.integrator = parse_integrator("albedo");
    const Image a = test::render(s, albedo, 4).linear;
    const Image img = test::render(s, settings_from_scene(s.render), 16).linear;
    const CameraData cam = camera_data(s.camera);
    const float ground_y = s.vertices[3 * model_triangles].y;
    Regions r;
    r.pixels = std::size_t(a.width) * a.height;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const float alb = a.at(x, y, 0);
            const double lum = 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
            if (std::abs(alb - 0.8f) < 1e-3f) {
                ++r.model;
                r.model_mean += lum;
                continue;
            }
            if (std::abs(alb - presentation::kGroundAlbedo) > 1e-3f) continue;
            int in_shadow = 0;
            const float jx[5] = {0, 1, 0, 1, 0.5f}, jy[5] = {0, 0, 1, 1, 0.5f};
            for (int k = 0; k < 5; ++k) {
                // The kernel's camera ray (kernels/camera.cl).
                const float u = 2.0f * (float(x) + jx[k]) / float(cam.width) - 1.0f;
                const float v = 1.0f - 2.0f * (float(y) + jy[k]) / float(cam.height);
                const glm::vec3 eye = load3(cam.eye);
                const glm::vec3 d = glm::normalize(load3(cam.forward) + u * load3(cam.right) + v * load3(cam.up));
                const glm::vec3 p = eye + d * ((ground_y - eye.y) / d.y);
                in_shadow += with_sun_for_shadow_ray && blocked(s, model_triangles, p, -sun_dir);
            }
            if (in_shadow == 5) {
                ++r.shadow;
                r.shadow_mean += lum;
            } else if (in_shadow == 0) {
                ++r.lit;
                r.lit_mean += lum;
            }
        }
    if (r.model) r.model_mean /= double(r.model);
    if (r.lit) r.lit_mean /= double(r.lit);
    if (r.shadow) r.shadow_mean /= double(r.shadow);
    std::printf("pixels %zu: model %zu (mean %.3f), lit ground %zu (mean %.3f), shadow %zu (mean %.3f)\n", r.pixels,
                r.model, r.model_mean, r.lit, r.lit_mean, r.shadow, r.shadow_mean);
    return r;
}

Scene small(Scene s) {
    s.camera.width = 64;
    s.camera.height = 48;
    s.render.max_depth = 4;
    return s;
}

// A presented model as a user gets it: the model, the lit ground and the
// model's shadow on it.
void expect_model_ground_and_shadow(const Scene& s) {
    const glm::vec3 sun = s.lights.at(0).direction;
    const Regions r = regions(s, 12, true, sun);
    // The model and the ground fill a good part of the frame.
    EXPECT_GT(r.model, r.pixels / 20) << "model pixels";
    EXPECT_GT(r.lit, r.pixels / 5) << "lit ground pixels";
    EXPECT_GE(r.shadow, 10u) << "ground pixels in the model's shadow";
    // In shadow the ground has only the sky: the sun's share (over half of
    // the lit ground's radiance, presentation.hpp) is gone.
    EXPECT_LT(r.shadow_mean, 0.6 * r.lit_mean);
    EXPECT_GT(r.lit_mean, 0.1);
    // The model stands out from the ground around it.
    EXPECT_GT(std::abs(r.model_mean - r.lit_mean), 0.1 * r.lit_mean);
}

TEST(PresentationRender, BareMeshShowsModelGroundAndShadow) { expect_model_ground_and_shadow(small(bare(kCube))); }

// Control: the same regions with the sun taken out. The shadow check above
// must then fail, or it would not be measuring the sun's shadow.
void expect_no_shadow_without_the_sun(Scene s) {
    const glm::vec3 sun = s.lights.at(0).direction;
    s.lights.clear();
    const Regions r = regions(s, 12, true, sun);
    ASSERT_GE(r.shadow, 10u);
    EXPECT_GE(r.shadow_mean, 0.6 * r.lit_mean);
}

TEST(PresentationRender, ControlWithoutTheSunHasNoShadow) { expect_no_shadow_without_the_sun(small(bare(kCube))); }

// The glTF cube, rendered as a user gets it: the model, the ground and the
// model's shadow, as for the OBJ cube above.
TEST(PresentationRender, BareGltfShowsModelGroundAndShadow) {
    expect_model_ground_and_shadow(small(bare_gltf(gltf_cube())));
}

TEST(PresentationRender, GltfControlWithoutTheSunHasNoShadow) {
    expect_no_shadow_without_the_sun(small(bare_gltf(gltf_cube())));
}

// The weakly emitting cube as a user gets it: lit like a bare mesh, with
// the ground and the model's shadow (it rendered black before its emitters'
// light was weighed).
TEST(PresentationRender, WeakEmitterIsLitLikeABareMesh) {
    Scene s = cube_with_emission_texture(1);
    present_model(s, {}, false);
    expect_model_ground_and_shadow(small(s));
}

TEST(PresentationRender, FlatYzModelIsVisible) {
    // Seen from +z, this plate was edge-on and every ray missed it.
    const Scene s = small(bare(kYzPlate));
    RenderSettings albedo = settings_from_scene(s.render);
    albedo.integrator = parse_integrator("albedo");
    const Image a = test::render(s, albedo, 4).linear;
    std::size_t model = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) model += std::abs(a.at(x, y, 0) - 0.8f) < 1e-3f;
    EXPECT_GT(model, std::size_t(a.width) * a.height / 10);
}

}  // namespace
}  // namespace clpath
