// Textures, alpha cut-outs and the glTF material through the renderer: a
// MASK cut-out is skipped by camera and shadow rays alike (with OPAQUE as the
// control), BLEND is stochastic coverage, the Suzanne model renders its
// base-colour texture, and renders the same when quantised as exporters write it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>

#include <gtest/gtest.h>

#include "render/device_scene.hpp"
#include "render/prepared_scene.hpp"
#include "scene/scene_builder.hpp"
#include "scene/load/scene_loader.hpp"
#include "scene/load/gltf_model.hpp"
#include "support/image_agreement.hpp"
#include "support/quantised_gltf.hpp"
#include "support/render_helpers.hpp"
#include "support/render_runs.hpp"
#include "support/temp_paths.hpp"

using namespace clpath;

namespace {

std::string scenes_dir() {
    return (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "scenes").lexically_normal().string();
}

// A 2x1 texture: the left half (u < 0.5) transparent, the right opaque; both black.
Texture cutout_texture() {
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {0, 0, 0, 0, 0, 0, 0, 255};
    t.wrap_s = t.wrap_t = CLP_WRAP_CLAMP;
    t.nearest = true;
    return t;
}

// A square of side 2 centred at c, spanned by axes a and b (front: a x b), u along a.
void add_square(Scene& s, glm::vec3 c, glm::vec3 a, glm::vec3 b, std::uint32_t material, bool with_uv) {
    const glm::vec3 p[4] = {c - a - b, c + a - b, c + a + b, c - a + b};
    const glm::vec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    std::vector<glm::vec3> v = {p[0], p[1], p[2], p[0], p[2], p[3]};
    std::vector<glm::vec2> t = {uv[0], uv[1], uv[2], uv[0], uv[2], uv[3]};
    SceneBuilder builder(s, 1000);
    VertexAttributes attr;
    if (with_uv) attr.uvs = &t;
    builder.add(v, {}, glm::mat4(1), {material}, "square", attr);
}

SceneMaterial cutout_material(std::uint32_t mode) {
    SceneMaterial m = gltf_material(glm::vec3(1), 1.0f, 0.5f);  // times the black texture: black metal
    m.texture[CLP_TEX_BASE] = 0;
    m.alpha_mode = mode;
    return m;
}

// Mean of channel 0 over the columns [x0, x1) of the image.
double column_mean(const Image& img, int x0, int x1) {
    double sum = 0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = x0; x < x1; ++x, ++n) sum += img.at(x, y, 0);
    return sum / n;
}

RenderSettings path_settings() {
    RenderSettings s;
    s.seed = 3;
    s.max_depth = 4;
    return s;
}

}  // namespace

// Camera rays: through the transparent half the white sky is seen exactly.
TEST(GltfRender, MaskCutoutSeenThroughByCameraRays) {
    for (std::uint32_t mode : {CLP_ALPHA_MASK, CLP_ALPHA_OPAQUE}) {
        Scene s;
        s.textures.push_back(cutout_texture());
        const std::uint32_t m = s.add_material("cutout", cutout_material(mode));
        add_square(s, glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), m, true);  // faces +z
        s.environment.color = glm::vec3(1);
        s.camera.eye = {0, 0, 3};
        s.camera.target = {0, 0, 0};
        s.camera.vfov_degrees = 20;  // the square fills the view
        s.camera.width = s.camera.height = 16;
        const Image img = test::render(s, path_settings(), 4).linear;
        const double left = column_mean(img, 0, 6), right = column_mean(img, 10, 16);
        // Camera looks down -z with right = +x... the texture's left half (u < 0.5) is at x < 0.
        const double open = std::max(left, right), closed = std::min(left, right);
        if (mode == CLP_ALPHA_MASK) {
            EXPECT_NEAR(open, 1.0, 1e-6) << "the sky, seen through the cut-out";
            EXPECT_LT(closed, 0.3) << "black metal reflecting the sky only at grazing Fresnel";
        } else {
            EXPECT_LT(open, 0.3) << "OPAQUE ignores alpha";
        }
    }
}

// Shadow and bounce rays: a horizontal cut-out square over a white floor, lit
// straight down by a directional light; the floor is lit only under the cut-out.
TEST(GltfRender, MaskCutoutLetsShadowRaysThrough) {
    for (std::uint32_t mode : {CLP_ALPHA_MASK, CLP_ALPHA_OPAQUE}) {
        Scene s;
        s.textures.push_back(cutout_texture());
        const std::uint32_t floor = s.add_material("floor", diffuse(glm::vec3(0.8f)));
        const std::uint32_t m = s.add_material("cutout", cutout_material(mode));
        add_square(s, glm::vec3(0), glm::vec3(0, 0, 10), glm::vec3(10, 0, 0), floor, true);  // faces +y
        add_square(s, glm::vec3(0, 1, 0), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0), m, true);  // u along z
        PunctualLight sun;
        sun.type = PunctualLight::Type::Directional;
        sun.direction = {0, -1, 0};
        sun.intensity = glm::vec3(1);
        s.lights.push_back(sun);
        // Looking straight down from below the square at the floor under it.
        s.camera.eye = {0, 0.5f, 0};
        s.camera.target = {0, 0, 0};
        s.camera.up = {0, 0, 1};
        s.camera.vfov_degrees = 90;
        s.camera.width = s.camera.height = 16;
        const Image img = test::render(s, path_settings(), 16).linear;
        // The floor under the square spans z in [-1/2, 1/2] of the view; the
        // square's transparent half is z < 0. Compare two bands of rows.
        double lit = 0, dark = 0;
        for (int x = 4; x < 12; ++x)
            for (int y = 0; y < 4; ++y) {
                lit += img.at(x, y, 0) / 32;
                dark += img.at(x, 15 - y, 0) / 32;
            }
        const double bright = std::max(lit, dark), dim = std::min(lit, dark);
        // Directly lit floor: 0.8 / pi of an irradiance of 1.
        if (mode == CLP_ALPHA_MASK) {
            EXPECT_NEAR(bright, 0.8 / 3.14159265, 0.02) << "under the cut-out the light arrives";
            EXPECT_LT(dim, 0.02) << "under the opaque half it does not";
        } else {
            EXPECT_LT(bright, 0.02) << "OPAQUE: all shadow";
        }
    }
}

// BLEND is stochastic coverage: a camera ray passes a surface of alpha a with
// probability 1 - a, so the image's expected value is a times the opaque
// surface's plus 1 - a times the white sky behind it. Each sample is one
// Bernoulli draw on top of the opaque surface's radiance, so over N samples
// the mean's standard deviation is at most sqrt(a (1 - a) / N) (values in
// [0, 1]); 16x16 pixels x 64 spp gives 0.0034, and 0.02 is 5.9 of it
// (two-sided false-failure rate 4e-9, with the opaque render's own noise
// smaller still). Control: MASK with the same alpha (below its cutoff) is
// fully transparent, 0.75 (1 - opaque) away from the expectation.
TEST(GltfRender, BlendIsStochasticCoverageForCameraRays) {
    const double a = 64.0 / 255.0;
    auto render_mode = [&](std::uint32_t mode) {
        Scene s;
        Texture t;
        t.width = t.height = 1;
        t.rgba8 = {0, 0, 0, 64};
        t.wrap_s = t.wrap_t = CLP_WRAP_CLAMP;
        t.nearest = true;
        s.textures.push_back(t);
        SceneMaterial m = gltf_material(glm::vec3(1), 0.0f, 0.5f);  // black base: only the specular layer
        m.texture[CLP_TEX_BASE] = 0;
        m.alpha_mode = mode;
        const std::uint32_t id = s.add_material("blend", m);
        add_square(s, glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), id, true);
        s.environment.color = glm::vec3(1);
        s.camera.eye = {0, 0, 3};
        s.camera.target = {0, 0, 0};
        s.camera.vfov_degrees = 20;  // the square fills the view
        s.camera.width = s.camera.height = 16;
        return column_mean(test::render(s, path_settings(), 64).linear, 0, 16);
    };
    const double opaque = render_mode(CLP_ALPHA_OPAQUE), blend = render_mode(CLP_ALPHA_BLEND);
    const double expected = a * opaque + (1 - a);
    ASSERT_LT(opaque, 0.3) << "the surface must differ from the sky, or coverage could not be seen";
    EXPECT_NEAR(blend, expected, 0.02) << "opaque " << opaque;
    EXPECT_GT(std::abs(render_mode(CLP_ALPHA_MASK) - expected), 0.02) << "control: MASK below its cutoff";
}

// The repository's Suzanne: its first-hit albedo shows the base-colour
// texture (colours within the texture's range, not the untextured white).
TEST(GltfRender, SuzanneShowsItsBaseColourTexture) {
    LoadOptions no_ground;  // every pixel that is not sky is the model's
    no_ground.presentation.ground = false;
    Scene s = load_scene(scenes_dir() + "/suzanne/Suzanne.gltf", no_ground);
    s.camera.width = 48;
    s.camera.height = 36;
    RenderSettings albedo;
    albedo.integrator = CLP_INTEGRATOR_ALBEDO;
    const Image img = test::render(s, albedo, 1).linear;
    // The texture's decoded colour range.
    const Texture& t = s.textures[0];
    glm::vec3 lo(1), hi(0);
    auto dec = [](int b) { double c = b / 255.0; return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4)); };
    for (std::size_t i = 0; i < t.rgba8.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], dec(t.rgba8[i + c]));
            hi[c] = std::max(hi[c], dec(t.rgba8[i + c]));
        }
    int on_model = 0;
    double mean_r = 0, mean_b = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            if (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2) == 0) continue;  // the sky
            ++on_model;
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(img.at(x, y, c), lo[c] - 1e-5f);
                EXPECT_LE(img.at(x, y, c), hi[c] + 1e-5f);
            }
            mean_r += img.at(x, y, 0);
            mean_b += img.at(x, y, 2);
        }
    ASSERT_GT(on_model, 100);  // the model covers about a tenth of the frame
    EXPECT_LT(mean_r / on_model, 0.9) << "not the untextured white";
    EXPECT_NE(mean_r, mean_b) << "coloured";
}

// Renders of a file holding the repository's Suzanne, seen through the
// original's camera (the presentation frames each file by its own bounds; a
// control made larger must show larger): K runs with independent seeds.
static std::vector<Image> suzanne_runs(const std::string& file, std::uint32_t seed0) {
    static const Scene original = load_scene(scenes_dir() + "/suzanne/Suzanne.gltf");
    Scene s = load_scene(file);
    s.camera = original.camera;
    s.camera.width = 48;
    s.camera.height = 36;
    RenderSettings st;
    st.max_depth = 4;
    return test::render_runs(s, st, 16, 8, seed0);
}

// A folder for rewritten Suzanne files, holding the model's two images.
static std::filesystem::path suzanne_folder(const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path out = test::temp_path(name);
    fs::create_directories(out);
    for (const char* png : {"Suzanne_BaseColor.png", "Suzanne_MetallicRoughness.png"})
        fs::copy_file(fs::path(scenes_dir()) / "suzanne" / png, out / png, fs::copy_options::overwrite_existing);
    return out;
}

static std::string write_json(const std::filesystem::path& folder, const std::string& name, const nlohmann::json& doc) {
    std::ofstream(folder / name) << doc.dump();
    return (folder / name).string();
}

// The same file with its one node 5 % larger: a control the comparison must reject.
static std::string larger_copy(const std::filesystem::path& folder, const nlohmann::json& doc) {
    nlohmann::json larger = doc;
    for (auto& s : larger["nodes"][0]["scale"]) s = s.get<float>() * 1.05f;
    return write_json(folder, "larger.gltf", larger);
}

// The repository's Suzanne quantised as gltfpack writes it by default
// (KHR_mesh_quantization: uint16 positions, int8 normals, uint16 texture
// coordinates mapped back by KHR_texture_transform on both textures) renders
// the same image as the original: its geometry moves by at most half a grid
// step (1/131070 of the model's size), far below what the pixels resolve.
// 8 runs per side with independent seeds; 8x8 blocks z-tested at a
// Sidak-corrected 1e-7 over all blocks (a false failure rarer than once in
// ten million runs). Controls: the model 5 % larger, and its base-colour and
// metallic-roughness images swapped, are rejected. (Its texture transform is
// near the identity and its base colour near uniform, so that dropping the
// transform is below the noise: the geometry test checks the transform.)
TEST(GltfRender, QuantisedSuzanneRendersLikeTheOriginal) {
    const std::filesystem::path out = suzanne_folder("quantised-suzanne");
    const GltfModel model = load_gltf(scenes_dir() + "/suzanne/Suzanne.gltf", LoadOptions{});
    const test::QuantisedGltf q = test::quantise_like_gltfpack(
        model.meshes[0][0], {"Suzanne_BaseColor.png", "Suzanne_MetallicRoughness.png"}, "q.bin");
    std::ofstream(out / "q.bin", std::ios::binary) << q.bin;
    nlohmann::json swapped = q.doc;
    std::swap(swapped["images"][0], swapped["images"][1]);

    const std::vector<Image> original = suzanne_runs(scenes_dir() + "/suzanne/Suzanne.gltf", 100);
    const auto same = test::image_agreement(original, suzanne_runs(write_json(out, "q.gltf", q.doc), 200), 8, 1e-7);
    EXPECT_TRUE(same.ok()) << same.describe();
    const auto swapped_images =
        test::image_agreement(original, suzanne_runs(write_json(out, "swapped.gltf", swapped), 300), 8, 1e-7);
    EXPECT_FALSE(swapped_images.ok()) << "control: images swapped: " << swapped_images.describe();
    const auto larger = test::image_agreement(original, suzanne_runs(larger_copy(out, q.doc), 400), 8, 1e-7);
    EXPECT_FALSE(larger.ok()) << "control: 5 % larger: " << larger.describe();
    std::printf("quantised: %s\nswapped images: %s\n5 %% larger: %s\n", same.describe().c_str(),
                swapped_images.describe().c_str(), larger.describe().c_str());
    std::filesystem::remove_all(out);
}

// gltfpack itself (Debian's, tools/install-deps.sh): its default output
// (14-bit positions, 8-bit normals, 12-bit texture coordinates under a
// texture transform, vertices merged and reindexed) and its -cc output (the
// same, EXT_meshopt_compression with its filters on top). The same comparison
// and the same 5 % control as above, for each.
TEST(GltfRender, GltfpackOutputRendersLikeTheOriginal) {
    if (std::system("command -v gltfpack > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "SKIPPED: gltfpack is not installed (tools/install-deps.sh installs it), nothing tested";
    const std::filesystem::path out = suzanne_folder("gltfpack-suzanne");
    const std::vector<Image> original = suzanne_runs(scenes_dir() + "/suzanne/Suzanne.gltf", 500);
    std::uint32_t seed = 600;
    for (const std::string options : {"", "-cc"}) {
        SCOPED_TRACE("gltfpack " + options);
        const std::string packed = (out / ("packed" + options + ".gltf")).string();
        const std::string command = "gltfpack " + options + " -i '" + scenes_dir() + "/suzanne/Suzanne.gltf' -o '" +
                                    packed + "' > /dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::ifstream in(packed);
        const nlohmann::json doc = nlohmann::json::parse(in);
        const nlohmann::json required = doc.at("extensionsRequired");
        EXPECT_NE(std::find(required.begin(), required.end(), "KHR_mesh_quantization"), required.end());
        if (options == "-cc") {
            EXPECT_NE(std::find(required.begin(), required.end(), "EXT_meshopt_compression"), required.end());
        }
        const auto same = test::image_agreement(original, suzanne_runs(packed, seed++), 8, 1e-7);
        EXPECT_TRUE(same.ok()) << same.describe();
        const auto larger = test::image_agreement(original, suzanne_runs(larger_copy(out, doc), seed++), 8, 1e-7);
        EXPECT_FALSE(larger.ok()) << "control: 5 % larger: " << larger.describe();
        std::printf("gltfpack %s: %s\n5 %% larger: %s\n", options.c_str(), same.describe().c_str(),
                    larger.describe().c_str());
    }
    std::filesystem::remove_all(out);
}

// Texture slots and coverage live in their own buffer, filled only for a
// scene whose kernels read them: a scene without textures or alpha keeps the
// material table (and the device memory) it had before those features, with
// one zero record in place of the extensions.
TEST(GltfRender, MaterialExtensionsOnlyForScenesWithTexturesOrAlpha) {
    const auto needs = [](const PreparedScene& p) {
        for (const auto& [what, bytes] : DeviceScene::memory_needs(p, test::node_layout()))
            if (what == "material extensions") return bytes;
        ADD_FAILURE() << "no material extensions entry";
        return std::size_t(0);
    };
    const auto plain = prepare_scene(test::small_cornell(8, 8), RenderSettings{});
    EXPECT_TRUE(plain->material_ext.empty());
    EXPECT_EQ(plain->summary.surface_flags & CLP_SCENE_MATERIAL_EXT, 0u);
    EXPECT_EQ(needs(*plain), sizeof(MaterialExt));

    const Scene suzanne = load_scene(scenes_dir() + "/suzanne/Suzanne.gltf");
    const auto textured = prepare_scene(suzanne, RenderSettings{});
    ASSERT_EQ(textured->material_ext.size(), suzanne.materials.size());
    EXPECT_NE(textured->summary.surface_flags & CLP_SCENE_MATERIAL_EXT, 0u);
    EXPECT_EQ(needs(*textured), suzanne.materials.size() * sizeof(MaterialExt));
    for (std::size_t i = 0; i < suzanne.materials.size(); ++i)
        for (int t = 0; t < 4; ++t) EXPECT_EQ(textured->material_ext[i].texture[t], suzanne.materials[i].texture[t]);

    // Alpha alone (a MASK material without a texture) needs them too: traversal reads the cutoff.
    Scene cut;
    SceneMaterial m = gltf_material(glm::vec3(1), 0, 1);
    m.alpha_mode = CLP_ALPHA_MASK;
    add_square(cut, glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), cut.add_material("mask", m), false);
    cut.environment.color = glm::vec3(1);
    EXPECT_EQ(prepare_scene(cut, RenderSettings{})->material_ext.size(), 1u);
}
