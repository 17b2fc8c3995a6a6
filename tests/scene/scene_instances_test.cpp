// A scene file's "instances" list on a mesh object: one mesh, many placements;
// bad entries named by file and field.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin_scenes.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/memory_files.hpp"

namespace clpath {
namespace {

using test::error_of;
using test::MemoryFiles;

const char* kHead = R"({"camera": {"eye": [0, 0, -3], "target": [0, 0, 0]},
  "materials": {"white": {"type": "diffuse"}, "lamp": {"type": "emitter", "emission": 4}},
  "objects": [{"type": "plane", "material": "white"}, )";

MemoryFiles tetra() {
    MemoryFiles files;
    files.files["scenes/tet.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    return files;
}

Scene parse(const std::string& object) {
    return parse_scene_file(std::string(kHead) + object + "]}", "scenes/s.json", tetra().options());
}
std::string parse_error(const std::string& object) { return error_of([&] { parse(object); }); }

TEST(SceneInstances, AMeshIsStoredOnceAndPlacedByEachEntry) {
    const Scene s = parse(R"({"type": "mesh", "file": "tet.obj", "material": "white",
        "transform": {"scale": 2},
        "instances": [{"translate": [1, 0, 0]},
                      {"matrix": [-1, 0, 0, 5,  0, 3, 0, 0,  0, 0, 0.5, 0]},
                      {"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}]})");
    EXPECT_EQ(s.triangle_count(), 2u);  // the plane
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].triangle_count(), 4u);
    // The object's own transform is in the mesh: a corner at 2 on x.
    float max_x = 0;
    for (auto v : s.meshes[0].vertices) max_x = std::max(max_x, v.x);
    EXPECT_FLOAT_EQ(max_x, 2.0f);
    ASSERT_EQ(s.instances.size(), 3u);
    EXPECT_EQ(s.instances[0].object_to_world[3], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(s.instances[1].object_to_world[0], glm::vec4(-1, 0, 0, 0));  // row-major in the file, column-major here
    EXPECT_EQ(s.instances[1].object_to_world[3], glm::vec4(5, 0, 0, 1));
    EXPECT_EQ(s.instances[1].object_to_world[1], glm::vec4(0, 3, 0, 0));
    EXPECT_EQ(s.placed_triangle_count(), 2u + 3u * 4u);
    // Flattened, the mirrored copy keeps its outside as its front: the same
    // winding rule as the loaders' (two corners swapped back).
    const Scene flat = flatten_instances(s);
    EXPECT_EQ(flat.triangle_count(), 14u);
}

TEST(SceneInstances, AnEmissiveMeshIsPlacedFlattened) {
    const Scene s = parse(R"({"type": "mesh", "file": "tet.obj", "material": "lamp",
        "instances": [{"translate": [1, 0, 0]}, {"translate": [3, 0, 0]}]})");
    EXPECT_TRUE(s.meshes.empty());
    EXPECT_TRUE(s.instances.empty());
    EXPECT_EQ(s.triangle_count(), 2u + 8u);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.notes.back().find("placed flattened"), std::string::npos) << s.notes.back();
}

// A mesh placed once costs the two-level walk more than it saves: its copy
// goes into the flat scene (benchmarks/results/pocl-epyc-2core/instancing).
TEST(SceneInstances, AMeshPlacedOnceIsPlacedFlattened) {
    const Scene s = parse(R"({"type": "mesh", "file": "tet.obj", "material": "white",
        "instances": [{"translate": [1, 0, 0], "scale": [1, 2, -1]}]})");
    EXPECT_TRUE(s.meshes.empty());
    EXPECT_TRUE(s.instances.empty());
    EXPECT_EQ(s.triangle_count(), 2u + 4u);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.notes.back().find("1 copy placed flattened, not instanced (a mesh placed once"), std::string::npos)
        << s.notes.back();
}

TEST(SceneInstances, BadEntriesAreNamedByFileAndField) {
    const std::string mesh = R"({"type": "mesh", "file": "tet.obj", "material": "white", "instances": )";
    struct Case {
        const char* instances;
        const char* expect;
    } cases[] = {
        {R"([{"scale": [1, 0, 1]}])", "scenes/s.json: objects[1].instances[0].scale: the transform is singular"},
        {R"([{"matrix": [1, 2, 3, 0,  2, 4, 6, 0,  0, 0, 1, 0]}])",
         "scenes/s.json: objects[1].instances[0].matrix: the transform is singular"},
        {R"([{"matrix": [1, 0, 0]}])", "objects[1].instances[0].matrix: expected 12 or 16 numbers"},
        {R"([{"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 1, 0, 1]}])",
         "objects[1].instances[0].matrix: the last row must be 0 0 0 1"},
        {R"([{"matrix": [1, 0, 0, 0], "translate": [1, 2, 3]}])", "give either matrix or translate/rotate/scale"},
        {R"([{"translate": "up"}])", "objects[1].instances[0].translate"},
        {R"([{"shift": [1, 0, 0]}])", "objects[1].instances[0]"},
        {R"([])", "objects[1].instances: an instances list needs at least one entry"},
        {R"({"translate": [1, 0, 0]})", "objects[1].instances"},
    };
    for (const auto& c : cases) {
        const std::string e = parse_error(mesh + c.instances + "}");
        EXPECT_NE(e.find(c.expect), std::string::npos) << c.instances << "\n  gave: " << e;
    }
    EXPECT_NE(parse_error(R"({"type": "mesh", "file": "none.obj", "material": "white", "instances": [{}]})")
                  .find("none.obj"),
              std::string::npos);
    EXPECT_NE(parse_error(R"({"type": "mesh", "file": "tet.obj", "material": "nothing", "instances": [{}]})")
                  .find("no material named 'nothing'"),
              std::string::npos);
}

TEST(SceneInstances, BuiltinBunniesRejectsBadCounts) {
    EXPECT_NE(error_of([] { builtin_scene("bunnies:2000000"); }).find("[1, 1000000]"), std::string::npos);
    EXPECT_NE(error_of([] { builtin_scene("bunnies:0"); }).find("bunnies:N"), std::string::npos);
    EXPECT_NE(error_of([] { builtin_scene("bunnies:x"); }).find("bunnies:N"), std::string::npos);
}

}  // namespace
}  // namespace clpath
