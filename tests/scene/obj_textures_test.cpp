// Textured OBJ/MTL materials in scenes: map_Kd and map_d decoded into the
// scene's textures (map_d's first channel as alpha), vertex colours kept,
// a missing image a warning naming its .mtl line, a mismatched one refused.
#include <gtest/gtest.h>

#include "memory_files.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/load/scene_loader.hpp"

using namespace clpath;
using namespace clpath::test;

namespace {

// "WxH" then one byte per texel, used for every channel: enough to tell images apart.
TextureImage grey_decode(const std::string& bytes, const std::string& name) {
    const auto x = bytes.find('x'), nl = bytes.find('\n');
    if (x == std::string::npos || nl == std::string::npos) throw Error(name + ": cannot decode the image");
    TextureImage t;
    t.width = std::stoi(bytes.substr(0, x));
    t.height = std::stoi(bytes.substr(x + 1, nl - x - 1));
    for (std::size_t i = nl + 1; i < bytes.size(); ++i)
        for (int c = 0; c < 4; ++c) t.rgba8.push_back(std::uint8_t(bytes[i]));
    return t;
}

MemoryFiles scene_files(const std::string& mask) {
    MemoryFiles f;
    f.files["s/scene.json"] = R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "m/quad.obj"}], "environment": {"color": 1}})";
    f.files["s/m/quad.obj"] = "mtllib quad.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
                              "usemtl leaf\nf 1/1 2/2 3/3\n";
    f.files["s/m/quad.mtl"] = "newmtl leaf\nmap_Kd img/leaf.png\nmap_d img/" + mask + "\n";
    f.files["s/m/img/leaf.png"] = std::string("2x1\n") + char(10) + char(20);
    f.files["s/m/img/mask.png"] = std::string("2x1\n") + char(0) + char(255);
    f.files["s/m/img/big.png"] = std::string("3x1\n") + char(0) + char(255) + char(0);
    return f;
}

Scene load(const MemoryFiles& f) {
    LoadOptions o = f.options();
    o.decode_texture = grey_decode;
    return parse_scene_file(f.files.at("s/scene.json"), "s/scene.json", o);
}

}  // namespace

TEST(ObjTextures, DiffuseAndAlphaMapsBecomeOneTexture) {
    const Scene s = load(scene_files("mask.png"));
    ASSERT_EQ(s.textures.size(), 1u);
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.rgba8, (std::vector<std::uint8_t>{10, 10, 10, 0, 20, 20, 20, 255}));
    const SceneMaterial& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(m.kind, CLP_MAT_GLTF);
    EXPECT_EQ(m.texture[CLP_TEX_BASE], 0);
    EXPECT_EQ(m.alpha_mode, CLP_ALPHA_MASK);
    ASSERT_EQ(s.uvs.size(), 3u);
    ASSERT_EQ(s.colors.size(), 3u);
    EXPECT_EQ(s.colors[0], glm::vec4(1, 0, 0, 1));
}

// A missing map loads as Blender loads it: the material without that map,
// with a warning naming the .mtl line and the path it resolved to. A map that
// is there but does not fit stays an error.
TEST(ObjTextures, MissingImageIsAWarningMismatchedImageAnError) {
    const Scene s = load(scene_files("gone.png"));
    bool warned = false;
    for (const auto& w : s.warnings)
        warned = warned || w.find("s/m/quad.mtl:3: map_d of material 'leaf': s/m/img/gone.png: no such file") != std::string::npos;
    EXPECT_TRUE(warned);
    const SceneMaterial& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(m.alpha_mode, CLP_ALPHA_OPAQUE) << "no mask to cut with";
    EXPECT_EQ(m.texture[CLP_TEX_BASE], 0) << "map_Kd, which is there, still applies";
    const std::string size = error_of([] { (void)load(scene_files("big.png")); });
    EXPECT_NE(size.find("s/m/img/big.png: map_d of material 'leaf' is 3x1, but its map_Kd is 2x1"), std::string::npos) << size;
}

TEST(ObjTextures, RepositoryTexturedScene) {
    const Scene s = load_scene(scenes_dir() + "/textured/textured.json");
    EXPECT_EQ(s.textures.size(), 4u);  // checker, fence, and Suzanne's two
    EXPECT_FALSE(s.colors.empty());
    bool fence = false;
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        fence = fence || (s.material_names[i].find(":fence") != std::string::npos && s.materials[i].alpha_mode == CLP_ALPHA_MASK);
    EXPECT_TRUE(fence);
}
