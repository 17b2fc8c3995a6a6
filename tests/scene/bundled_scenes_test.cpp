// The scenes shipped in scenes/ and the generated scaling scenes: each loads
// cleanly and holds what its description promises.
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "scene/builtin_scenes.hpp"
#include "scene/memory_files.hpp"
#include "scene/load/scene_loader.hpp"

namespace clpath {
namespace {

Scene bundled(const std::string& name) { return load_scene(test::scenes_dir() + "/" + name + ".json"); }

std::size_t count_material(const Scene& s, const std::string& name) {
    std::size_t n = 0;
    for (auto m : s.triangle_material) n += s.material_names[m] == name;
    return n;
}

TEST(BundledScenes, AllLoadCleanlyAndEmit) {
    std::size_t found = 0;
    for (const auto& entry : std::filesystem::directory_iterator(test::scenes_dir())) {
        if (entry.path().extension() != ".json") continue;
        ++found;
        SCOPED_TRACE(entry.path().string());
        const Scene s = load_scene(entry.path().string());
        EXPECT_GT(s.triangle_count(), 0u);
        EXPECT_TRUE(s.has_emitter());
        EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
        EXPECT_NO_THROW(camera_data(s.camera));
    }
    EXPECT_GE(found, 4u);
}

// Per material: the set of corner positions (rounded to 1e-5) and the total area.
using Signature = std::map<std::string, std::pair<std::set<std::tuple<long, long, long>>, double>>;
Signature signature(const Scene& s) {
    Signature sig;
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        auto& [points, area] = sig[s.material_names[s.triangle_material[t]]];
        for (int c = 0; c < 3; ++c) {
            const glm::vec3 v = s.vertices[3 * t + c] * 1e5f;
            points.insert({std::lround(v.x), std::lround(v.y), std::lround(v.z)});
        }
        area += 0.5 * glm::length(glm::cross(s.vertices[3 * t + 1] - s.vertices[3 * t], s.vertices[3 * t + 2] - s.vertices[3 * t]));
    }
    return sig;
}

TEST(BundledScenes, ThesisDiffuseIsTheBuiltInScene) {
    const Scene file = bundled("cornell-thesis-diffuse");
    const Scene code = cornell_thesis_scene();
    EXPECT_EQ(file.triangle_count(), 196u);
    EXPECT_EQ(file.material_names, code.material_names);
    for (std::size_t i = 0; i < code.materials.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(file.materials[i].albedo[c], code.materials[i].albedo[c]);
            EXPECT_FLOAT_EQ(file.materials[i].emission[c], code.materials[i].emission[c]);
        }
    EXPECT_EQ(file.materials[3].flags, CLP_MATF_TWO_SIDED_EMISSION);
    // The same surfaces (triangulated alike or not), material by material.
    const Signature a = signature(file), b = signature(code);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [name, sb] : b) {
        SCOPED_TRACE(name);
        const auto& sa = a.at(name);
        EXPECT_NEAR(sa.second, sb.second, 1e-5);
        EXPECT_EQ(sa.first.size(), sb.first.size());
        std::size_t close = 0;
        for (const auto& p : sa.first)
            for (const auto& q : sb.first)
                if (std::abs(std::get<0>(p) - std::get<0>(q)) <= 2 && std::abs(std::get<1>(p) - std::get<1>(q)) <= 2 &&
                    std::abs(std::get<2>(p) - std::get<2>(q)) <= 2) {
                    ++close;
                    break;
                }
        EXPECT_EQ(close, sa.first.size());
    }
    EXPECT_EQ(file.camera.eye, code.camera.eye);
    EXPECT_NEAR(file.camera.vfov_degrees, code.camera.vfov_degrees, 1e-4f);
    EXPECT_EQ(file.camera.width, 800);
    EXPECT_EQ(file.camera.height, 640);
}

TEST(BundledScenes, ThesisHasTheThesisTextMaterials) {
    const Scene s = bundled("cornell-thesis");
    EXPECT_EQ(s.triangle_count(), 196u);
    EXPECT_EQ(count_material(s, "glass"), 80u);        // sphere 1
    EXPECT_EQ(count_material(s, "glossy"), 12u + 80u);  // box 2 and sphere 2
    const auto& names = s.material_names;
    const Material& glass = s.materials[std::find(names.begin(), names.end(), "glass") - names.begin()];
    EXPECT_EQ(glass.kind, CLP_MAT_DIELECTRIC);
    EXPECT_FLOAT_EQ(glass.ior, 1.51714f);
    EXPECT_FLOAT_EQ(glass.albedo[2], 0.9f);
    const Material& glossy = s.materials[std::find(names.begin(), names.end(), "glossy") - names.begin()];
    EXPECT_EQ(glossy.kind, CLP_MAT_CONDUCTOR);
    EXPECT_FLOAT_EQ(glossy.roughness, 0.09f);
    // The glossy box is on the image's left: +x, since image right is -x.
    glm::vec3 centre(0);
    std::size_t n = 0;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        if (names[s.triangle_material[t]] == "glossy" && n < 36) {
            for (int c = 0; c < 3; ++c) centre += s.vertices[3 * t + c];
            n += 3;
        }
    EXPECT_GT(centre.x / float(n), 0.0f);
}

TEST(BundledScenes, ClassicCornellBoxIsThePublishedOne) {
    const Scene s = bundled("cornell-classic");
    EXPECT_EQ(s.triangle_count(), 32u);
    EXPECT_EQ(s.camera.eye, glm::vec3(278, 273, -800));
    EXPECT_NEAR(s.camera.vfov_degrees, 39.3077f, 1e-4f);
    double light_area = 0;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        if (s.material_names[s.triangle_material[t]] == "light") {
            const glm::vec3* v = &s.vertices[3 * t];
            const glm::vec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
            light_area += 0.5 * glm::length(n);
            EXPECT_LT(n.y, 0.0f);  // it shines down
        }
    EXPECT_NEAR(light_area, 130.0 * 105.0, 1e-3);
}

TEST(BundledScenes, BunnyStandsInTheRoom) {
    const Scene s = bundled("bunny");
    EXPECT_EQ(s.triangle_count(), 69666u + 12u);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        if (s.material_names[s.triangle_material[t]] == "bunny")
            for (int c = 0; c < 3; ++c) {
                lo = glm::min(lo, s.vertices[3 * t + c]);
                hi = glm::max(hi, s.vertices[3 * t + c]);
            }
    EXPECT_NEAR(lo.y, -0.1f, 0.01f);  // on the floor
    EXPECT_GT(lo.x, -0.5f);
    EXPECT_LT(hi.x, 0.5f);
    EXPECT_LT(hi.y, 0.85f);  // under the lamp
}

TEST(ScalingScenes, CountFollowsTheRequestAndSizeStaysFixed) {
    glm::vec3 first_lo(0), first_hi(0);
    for (std::size_t n : {100u, 1000u, 100000u, 1000000u}) {
        const Scene s = load_scene("scaling:" + std::to_string(n));
        EXPECT_NEAR(double(s.triangle_count()), double(n), 0.02 * double(n) + 8) << n;
        EXPECT_EQ(s.name, "scaling-" + std::to_string(s.triangle_count()));
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (std::size_t i = 36; i < s.vertices.size(); ++i) {
            lo = glm::min(lo, s.vertices[i]);
            hi = glm::max(hi, s.vertices[i]);
        }
        if (n == 100) {
            first_lo = lo;
            first_hi = hi;
        } else {
            EXPECT_NEAR(glm::length(lo - first_lo), 0.0f, 0.05f) << n;
            EXPECT_NEAR(glm::length(hi - first_hi), 0.0f, 0.05f) << n;
        }
        EXPECT_GT(lo.y, -0.1f);  // above the floor
    }
    EXPECT_EQ(load_scene("scaling:1e4").triangle_count(), load_scene("scaling:10000").triangle_count());
}

}  // namespace
}  // namespace clpath
