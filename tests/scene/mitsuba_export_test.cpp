// clpath export --format mitsuba: the scene dictionary names a BSDF for every
// material kind, an emitter for every light kind, the camera and the depth
// Mitsuba needs, and the meshes hold every triangle once (a two-sided
// emitter's twice: its back copy reversed and behind it). That Mitsuba
// renders the same images is tests/references/mitsuba_agreement_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <array>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/export/mitsuba_export.hpp"
#include "scene/load/scene_loader.hpp"
#include "scene/memory_files.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

using json = nlohmann::json;

std::string repo_file(const std::string& rel) { return test::scenes_dir() + "/../" + rel; }

struct Parsed {
    json doc;
    std::map<std::string, std::vector<std::array<glm::dvec3, 3>>> tris;  // per mesh file
};

Parsed parse(const MitsubaExport& e) {
    Parsed p;
    p.doc = json::parse(e.json);
    for (const auto& [name, text] : e.meshes) {
        std::vector<glm::dvec3> v;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream l(line);
            std::string tag;
            l >> tag;
            if (tag == "v") {
                glm::dvec3 q;
                l >> q.x >> q.y >> q.z;
                v.push_back(q);
            } else if (tag == "f") {
                std::array<glm::dvec3, 3> t;
                for (auto& c : t) {
                    std::string idx;
                    l >> idx;
                    c = v.at(std::stoul(idx) - 1);
                }
                p.tris[name].push_back(t);
            }
        }
    }
    return p;
}

TEST(MitsubaExport, CornellThesisMaterialsDepthAndCamera) {
    const Scene s = load_scene(test::scenes_dir() + "/cornell-thesis.json");
    const Parsed p = parse(export_mitsuba_scene(s, "thesis", "test"));
    const json& sc = p.doc["scene"];
    EXPECT_EQ(sc["integrator"]["type"], "path");
    EXPECT_EQ(sc["integrator"]["max_depth"].get<int>(), int(s.render.max_depth) + 1);
    EXPECT_EQ(sc["bsdf-default"]["bsdf"]["type"], "diffuse");
    EXPECT_EQ(sc["bsdf-glass"]["type"], "dielectric");
    EXPECT_NEAR(sc["bsdf-glass"]["int_ior"].get<double>(), 1.51714, 1e-6);
    EXPECT_EQ(sc["bsdf-glossy"]["bsdf"]["type"], "principled");
    EXPECT_EQ(sc["bsdf-glossy"]["bsdf"]["metallic"].get<double>(), 1.0);
    // The camera sits at the origin; the target keeps its offset from the eye.
    const json& cam = sc["sensor"]["clpath_look_at"];
    EXPECT_EQ(cam["origin"], json::array({0.0, 0.0, 0.0}));
    EXPECT_NEAR(cam["target"][2].get<double>(), double(s.camera.target.z) - double(s.camera.eye.z), 1e-7);
    EXPECT_EQ(sc["sensor"]["fov_axis"], "y");
    EXPECT_EQ(sc["sensor"]["film"]["rfilter"]["type"], "box");
    // Every triangle once, and the two-sided lamp twice.
    std::size_t n = 0;
    for (const auto& [name, t] : p.tris) n += t.size();
    std::size_t lamp = p.tris.at("thesis-emissive.obj").size();
    EXPECT_EQ(n, s.triangle_count() + lamp);
    ASSERT_TRUE(sc.contains("shape-emissive-back"));
    EXPECT_EQ(sc["shape-emissive-back"]["emitter"]["type"], "area");
    // The back copy faces the other way and lies behind the front.
    const auto& front = p.tris.at("thesis-emissive.obj");
    const auto& back = p.tris.at("thesis-emissive-back.obj");
    ASSERT_EQ(front.size(), back.size());
    for (std::size_t i = 0; i < front.size(); ++i) {
        const glm::dvec3 nf = glm::normalize(glm::cross(front[i][1] - front[i][0], front[i][2] - front[i][0]));
        const glm::dvec3 nb = glm::normalize(glm::cross(back[i][1] - back[i][0], back[i][2] - back[i][0]));
        EXPECT_NEAR(glm::dot(nf, nb), -1.0, 1e-6);
        const double behind = glm::dot(back[i][0] - front[i][0], nf);
        EXPECT_LT(behind, 0.0);
        EXPECT_GT(behind, -1e-4);
    }
}

TEST(MitsubaExport, ThinLensIsMitsubasThinlensSensor) {
    Scene s = load_scene(repo_file("benchmarks/references/scenes/thin-lens.json"));
    const json lens = parse(export_mitsuba_scene(s, "l", "test")).doc["scene"]["sensor"];
    EXPECT_EQ(lens["type"], "thinlens");
    EXPECT_NEAR(lens["aperture_radius"].get<double>(), 0.12, 1e-7);
    EXPECT_NEAR(lens["focus_distance"].get<double>(), 4.0, 1e-7);
    s.camera.focus_distance = 0;  // the target's distance
    const json target = parse(export_mitsuba_scene(s, "l", "test")).doc["scene"]["sensor"];
    EXPECT_NEAR(target["focus_distance"].get<double>(), std::sqrt(0.4 * 0.4 + 4 * 4), 1e-6);
    s.camera.aperture_radius = 0;
    const json pinhole = parse(export_mitsuba_scene(s, "l", "test")).doc["scene"]["sensor"];
    EXPECT_EQ(pinhole["type"], "perspective");
    EXPECT_FALSE(pinhole.contains("aperture_radius"));
}

TEST(MitsubaExport, EveryLightKindAndRoughGlass) {
    Scene s = load_scene(repo_file("benchmarks/references/scenes/punctual-lights.json"));
    const json lights = parse(export_mitsuba_scene(s, "p", "test")).doc["scene"];
    EXPECT_EQ(lights["light-0"]["type"], "point");
    EXPECT_EQ(lights["light-1"]["type"], "spot");
    EXPECT_EQ(lights["light-1"]["cutoff_angle"], lights["light-1"]["beam_width"]);  // Mitsuba's falloff off
    EXPECT_EQ(lights["light-1"]["clpath_spot_falloff"]["inner_degrees"].get<double>(), 20.0);
    EXPECT_EQ(lights["light-2"]["type"], "directional");
    EXPECT_EQ(lights["bsdf-mirror"]["bsdf"]["type"], "conductor");
    EXPECT_EQ(lights["bsdf-mirror"]["bsdf"]["material"], "none");
    // The point light moves with the scene (camera at the origin).
    EXPECT_NEAR(lights["light-0"]["position"][1].get<double>(), 1.4 - 1.6, 1e-6);

    Scene g = load_scene(repo_file("benchmarks/references/scenes/rough-glass-sky.json"));
    const json sky = parse(export_mitsuba_scene(g, "g", "test")).doc["scene"];
    EXPECT_EQ(sky["bsdf-frost"]["type"], "roughdielectric");
    EXPECT_NEAR(sky["bsdf-frost"]["alpha"].get<double>(), 0.09, 1e-6);  // roughness^2
    EXPECT_EQ(sky["environment"]["type"], "envmap");
    EXPECT_TRUE(std::filesystem::path(sky["environment"]["filename"].get<std::string>()).is_absolute());
    EXPECT_EQ(sky["environment"]["clpath_env_rotation_degrees"].get<double>(), 30.0);
    EXPECT_EQ(sky["shape-floor"]["face_normals"], true);

    Scene m = load_scene(repo_file("benchmarks/references/scenes/metals.json"));
    const json metals = parse(export_mitsuba_scene(m, "m", "test")).doc["scene"];
    EXPECT_EQ(metals["environment"]["type"], "constant");
    EXPECT_EQ(metals["shape-chalk"]["face_normals"], false);  // shading normals travel as vn
}

// The entry whose key starts with `prefix` and holds `part` (a glTF
// material's name carries its file's path as the scene named it).
const json& entry(const json& scene, const std::string& prefix, const std::string& part) {
    for (const auto& [key, value] : scene.items())
        if (key.rfind(prefix, 0) == 0 && key.find(part) != std::string::npos) return value;
    throw std::runtime_error("no " + prefix + "..." + part + "...");
}

// The glTF material: the plugin, or principled where metallic is 1
// everywhere; textures as raw texels with their channel, factor, sRGB flag,
// filter and wrap mode; wrappers for normal maps and cut-outs.
TEST(MitsubaExport, GltfMaterialsAndTextures) {
    const Scene t = load_scene(repo_file("benchmarks/references/scenes/gltf-textured.json"));
    const MitsubaExport et = export_mitsuba_scene(t, "t", "test");
    const json tex = parse(et).doc["scene"];
    const json& floor = entry(tex, "bsdf-", "checker-floor")["bsdf"];
    EXPECT_EQ(floor["type"], "gltf_metallic_roughness");
    EXPECT_EQ(floor["base_color"]["type"], "bitmap");
    EXPECT_EQ(floor["base_color"]["filter_type"], "bilinear");
    EXPECT_EQ(floor["base_color"]["wrap_mode"], "repeat");
    EXPECT_EQ(floor["base_color"]["clpath_texture"]["srgb"], true);
    EXPECT_EQ(floor["base_color"]["clpath_texture"]["channels"], "rgb");
    EXPECT_EQ(entry(tex, "bsdf-", "ramp-clamp")["bsdf"]["base_color"]["wrap_mode"], "clamp");
    EXPECT_EQ(entry(tex, "bsdf-", "checker-mirror")["bsdf"]["base_color"]["wrap_mode"], "mirror");
    EXPECT_EQ(entry(tex, "shape-", "checker-floor")["flip_tex_coords"], false);
    // One texel file per texture, however many uses (the base colour is also
    // the coverage where a material has alpha), 16x16 RGBA8.
    std::map<std::string, std::size_t> sizes;
    for (const auto& [name, bytes] : et.textures) sizes[name] = bytes.size();
    EXPECT_EQ(sizes.size(), t.textures.size());
    EXPECT_EQ(sizes.at(floor["base_color"]["clpath_texture"]["file"].get<std::string>()), 16u * 16u * 4u);
    // Texture coordinates go out as clpath has them (v down; Mitsuba's flip off).
    for (const auto& [name, text] : et.meshes) {
        if (name.find("checker-floor") == std::string::npos) continue;
        EXPECT_NE(text.find("\nvt 0 0\n"), std::string::npos) << text;
        EXPECT_NE(text.find("\nvt 3 3\n"), std::string::npos) << text;
        EXPECT_NE(text.find("\nf 1/1/1 2/2/2 3/3/3\n"), std::string::npos) << text;
    }

    const Scene m = load_scene(repo_file("benchmarks/references/scenes/gltf-metals.json"));
    const json metals = parse(export_mitsuba_scene(m, "m", "test")).doc["scene"];
    const json& gold = entry(metals, "bsdf-", "gold-stripes")["bsdf"];
    EXPECT_EQ(gold["type"], "principled");
    EXPECT_EQ(gold["roughness"]["clpath_texture"]["channels"], "g");
    const json& ramp = entry(metals, "bsdf-", "metal-ramp")["bsdf"];
    EXPECT_EQ(ramp["type"], "gltf_metallic_roughness");
    EXPECT_EQ(ramp["metallic"]["clpath_texture"]["channels"], "b");
    EXPECT_EQ(ramp["metallic"]["clpath_texture"]["srgb"], false);
    EXPECT_EQ(metals["integrator"]["type"], "path");

    const Scene c = load_scene(repo_file("benchmarks/references/scenes/gltf-cutout.json"));
    const json cut = parse(export_mitsuba_scene(c, "c", "test")).doc["scene"];
    const json& sheet = entry(cut, "bsdf-", "holes");
    EXPECT_EQ(sheet["type"], "mask");
    EXPECT_EQ(sheet["opacity"]["type"], "threshold");
    EXPECT_EQ(sheet["opacity"]["cutoff"].get<double>(), 0.5);
    EXPECT_EQ(sheet["opacity"]["texture"]["clpath_texture"]["channels"], "a");
    EXPECT_EQ(cut["integrator"]["type"], "volpath");  // its shadow rays pass the holes

    const Scene n = load_scene(repo_file("benchmarks/references/scenes/gltf-normal-map.json"));
    const json nm = parse(export_mitsuba_scene(n, "n", "test")).doc["scene"];
    const json& bumpy = entry(nm, "bsdf-", "bumps");
    EXPECT_EQ(bumpy["type"], "twosided");
    EXPECT_EQ(bumpy["bsdf_0_front"]["type"], "normalmap");
    EXPECT_NEAR(bumpy["bsdf_0_front"]["normalmap"]["clpath_texture"]["normal_scale"].get<double>(), 0.8, 1e-6);
    EXPECT_NEAR(bumpy["bsdf_1_back"]["normalmap"]["clpath_texture"]["normal_scale"].get<double>(), -0.8, 1e-6);
    EXPECT_EQ(bumpy["bsdf_0_front"]["bsdf"]["type"], "gltf_metallic_roughness");

    // The glTF layers: the plugin's parameters; a transmitting BSDF is two-sided itself.
    const Scene cc = load_scene(repo_file("benchmarks/references/scenes/gltf-clearcoat.json"));
    const json coat = parse(export_mitsuba_scene(cc, "cc", "test")).doc["scene"];
    const json& stripes = entry(coat, "bsdf-", "coat-stripes");
    EXPECT_EQ(stripes["type"], "twosided");
    EXPECT_EQ(stripes["bsdf"]["type"], "gltf_metallic_roughness");
    EXPECT_EQ(stripes["bsdf"]["clearcoat"]["clpath_texture"]["channels"], "r");
    EXPECT_EQ(stripes["bsdf"]["clearcoat_roughness"]["clpath_texture"]["channels"], "g");
    EXPECT_NEAR(stripes["bsdf"]["clearcoat_roughness"]["clpath_texture"]["scale"].get<double>(), 0.3, 1e-6);
    const json& metal = entry(coat, "bsdf-", "coated-metal")["bsdf"];
    EXPECT_EQ(metal["type"], "gltf_metallic_roughness") << "a coated metal is not principled's metal";
    EXPECT_NEAR(metal["clearcoat_roughness"].get<double>(), 0.05, 1e-6);
    const Scene tr = load_scene(repo_file("benchmarks/references/scenes/gltf-transmission.json"));
    const json trans = parse(export_mitsuba_scene(tr, "tr", "test")).doc["scene"];
    const json& glass = entry(trans, "bsdf-", "thin-glass");
    EXPECT_EQ(glass["type"], "gltf_metallic_roughness");
    EXPECT_EQ(glass["transmits"], true);
    EXPECT_NEAR(glass["transmission"].get<double>(), 1.0, 1e-6);
    EXPECT_EQ(entry(trans, "bsdf-", "tinted-stripes")["transmission"]["clpath_texture"]["channels"], "r");
}

// What Mitsuba would be given differently is refused, naming the material.
TEST(MitsubaExport, RefusesWhatMitsubaWouldModelDifferently) {
    const Scene n = load_scene(repo_file("benchmarks/references/scenes/gltf-normal-map.json"));
    Scene mirrored = n;
    for (auto& uv : mirrored.uvs) uv.x = -uv.x;
    EXPECT_THROW(export_mitsuba_scene(mirrored, "x", "test"), Error);
    Scene colours = n;  // vertex colours on the lamp (an emitter)
    colours.colors.assign(colours.vertices.size(), glm::vec4(0.5f, 0.5f, 0.5f, 1));
    EXPECT_THROW(export_mitsuba_scene(colours, "x", "test"), Error);
    colours.colors.assign(colours.vertices.size(), glm::vec4(1));  // all white: ignored
    EXPECT_NO_THROW(export_mitsuba_scene(colours, "x", "test"));
    Scene wraps = n;
    wraps.textures.at(0).wrap_t = CLP_WRAP_CLAMP;
    EXPECT_THROW(export_mitsuba_scene(wraps, "x", "test"), Error);
    EXPECT_NO_THROW(export_mitsuba_scene(n, "x", "test"));
    // A coat with its own normal map; transmission with a normal map.
    Scene coat_normal = n;
    for (auto& m : coat_normal.materials)
        if (m.kind == CLP_MAT_GLTF) {
            m.clearcoat = 1;
            m.texture[CLP_TEX_CLEARCOAT_NORMAL] = m.texture[CLP_TEX_NORMAL];
        }
    EXPECT_THROW(export_mitsuba_scene(coat_normal, "x", "test"), Error);
    Scene transmits = n;
    for (auto& m : transmits.materials)
        if (m.kind == CLP_MAT_GLTF) m.transmission = 1;
    EXPECT_THROW(export_mitsuba_scene(transmits, "x", "test"), Error);
}

// An instanced scene flattened (as `clpath export` does) gives its flat
// triangles zero shading normals, clpath's "shade flat here"; Mitsuba
// refuses a zero normal, so each is written as its triangle's own.
TEST(MitsubaExport, ZeroShadingNormalsAreWrittenAsTheTrianglesOwn) {
    const Scene inst = load_scene(repo_file("benchmarks/references/scenes/gltf-instances.json"));
    ASSERT_FALSE(inst.instances.empty());
    const Scene flat = flatten_instances(inst);
    ASSERT_FALSE(flat.normals.empty());
    const MitsubaExport e = export_mitsuba_scene(flat, "i", "test");
    std::size_t normals = 0;
    for (const auto& [name, text] : e.meshes) {
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            if (line.rfind("vn ", 0) != 0) continue;
            std::istringstream l(line.substr(3));
            glm::dvec3 n;
            l >> n.x >> n.y >> n.z;
            EXPECT_NEAR(glm::length(n), 1.0, 1e-6) << name << ": " << line;
            ++normals;
        }
    }
    EXPECT_GT(normals, 0u);
}

TEST(MitsubaExport, RefusesAnEmptyScene) {
    Scene s;
    EXPECT_THROW(export_mitsuba_scene(s, "x", "test"), Error);
}

}  // namespace
}  // namespace clpath
