// Loaded scenes on the device: a scene without an emitter renders black (and
// nothing else), and kept fuzz findings load or fail cleanly.
#include <filesystem>

#include <gtest/gtest.h>

#include "render/settings.hpp"
#include "scene/memory_files.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/render_helpers.hpp"

namespace clpath {
namespace {

TEST(SceneRender, NoEmitterIsHonestlyBlack) {
    const Scene s = load_scene((std::filesystem::path(__FILE__).parent_path() / "data" / "no-emitter.json").string());
    ASSERT_FALSE(s.has_emitter());
    const RenderedImage img = test::render(s, settings_from_scene(s.render), 4);
    ASSERT_EQ(img.linear.width, 32);
    for (float v : img.linear.rgb) ASSERT_EQ(v, 0.0f);
}

TEST(SceneRender, LitSceneIsNotBlack) {
    // The same box with an emitting floor under it: the test above can fail.
    test::MemoryFiles files;
    const Scene s = parse_scene_file(R"({"camera": {"eye": [0, 0, -3], "target": [0, 0, 0], "resolution": [32, 24]},
        "materials": {"white": {"type": "diffuse"}, "lamp": {"type": "emitter", "emission": 2, "two_sided": true}},
        "objects": [{"type": "box", "material": "white"},
                    {"type": "plane", "material": "lamp", "size": [4, 4], "transform": {"translate": [0, -0.6, 0]}}]})",
                                     "lit.json", files.options());
    const RenderedImage img = test::render(s, settings_from_scene(s.render), 4);
    double sum = 0;
    for (float v : img.linear.rgb) sum += v;
    EXPECT_GT(sum, 0.0);
}

// Inputs that once crashed a fuzz target (tests/fuzz/regressions/): in the
// ordinary build too, each gives a scene or a clpath::Error, nothing else.
TEST(FuzzRegressions, KeptInputsLoadOrFailCleanly) {
    const auto root = std::filesystem::path(__FILE__).parent_path() / ".." / "fuzz" / "regressions";
    std::size_t n = 0;
    for (const auto& target : {"scene_file", "obj"}) {
        if (!std::filesystem::exists(root / target)) continue;
        for (const auto& e : std::filesystem::directory_iterator(root / target)) {
            SCOPED_TRACE(e.path().string());
            const std::string text = read_text_file(e.path().string());
            test::MemoryFiles files;
            try {
                if (std::string(target) == "scene_file") {
                    files.files["fuzz/mesh.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
                    (void)parse_scene_file(text, "fuzz/scene.json", files.options());
                } else {
                    files.files["fuzz/mesh.obj"] = text.substr(0, text.find("\n#MTL\n"));
                    (void)obj_scene("fuzz/mesh.obj", files.options());
                }
            } catch (const Error&) {
            }
            ++n;
        }
    }
    EXPECT_GE(n, 1u);
}

}  // namespace
}  // namespace clpath
