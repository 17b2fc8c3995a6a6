// What tinygltf would take on trust is refused before it parses: JSON nested
// past the limit (its recursion overflowed the stack), node hierarchies that
// expand combinatorially or loop, GLB containers of other versions, and
// fields of the wrong type or range that it read as their defaults. Each
// refusal names the file and the field; each has a control that loads.
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_document.hpp"
#include "scene/load/gltf_scene.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {


bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The document with `extras` nested `depth` levels deep, arrays and objects alternating.
std::string with_extras(const GltfBuilder& g, int depth) {
    std::string open, close;
    for (int i = 0; i < depth; ++i) {
        open += i % 2 ? "[" : "{\"k\":";
        close = (i % 2 ? "]" : "}") + close;
    }
    std::string text = g.embedded();
    return text.substr(0, text.size() - 1) + ",\"extras\":" + open + "1" + close + "}";
}

// Nodes 0..levels-1 each list the next node twice; the last places the quad.
GltfBuilder doubling_chain(int levels) {
    GltfBuilder g = quad_model();
    g.doc["nodes"] = json::array();
    for (int i = 0; i < levels; ++i) g.doc["nodes"].push_back({{"children", {i + 1, i + 1}}});
    g.doc["nodes"].push_back({{"mesh", 0}});
    return g;
}

std::string glb_with_version(const std::string& glb, std::uint32_t version) {
    std::string b = glb;
    std::memcpy(b.data() + 4, &version, 4);
    return b;
}

TEST(GltfDocument, DeepJsonIsRefusedBeforeParsing) {
    const GltfBuilder g = quad_model();
    // 20,000 levels overflowed tinygltf's recursion (a segfault); now a message.
    for (std::size_t depth : {gltf::kMaxJsonDepth + 1, std::size_t(20000)}) {
        const std::string e = gltf_text_error("deep.gltf", with_extras(g, int(depth)));
        EXPECT_TRUE(has(e, "deep.gltf: the JSON nests arrays and objects deeper than 512 levels (at byte ")) << e;
    }
    std::string glb = g.glb();
    const std::string deep_glb = gltf::glb_with_json(glb, with_extras(g, 20000));
    EXPECT_TRUE(has(gltf_text_error("deep.glb", deep_glb), "deep.glb: the JSON nests arrays and objects deeper than 512"));
    // Brackets inside strings are text, not nesting.
    GltfBuilder quoted = quad_model();
    quoted.doc["asset"]["generator"] = std::string(5000, '[');
    EXPECT_EQ(gltf_text_scene("q.gltf", quoted.embedded()).triangle_count(), 2u);
    // Control: nesting up to the limit loads (the quad's own document adds 1 level).
    EXPECT_EQ(gltf_text_scene("ok.gltf", with_extras(g, int(gltf::kMaxJsonDepth) - 1)).triangle_count(), 2u);
}

TEST(GltfDocument, NodePathsPastTheLimitAreRefusedQuickly) {
    // 2^40 paths to the quad: counted, not walked.
    const auto start = std::chrono::steady_clock::now();
    const std::string e = gltf_text_error("dag.gltf", doubling_chain(40).embedded());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(has(e, "dag.gltf: scenes[0].nodes: the node hierarchy places more than 1000000 nodes")) << e;
    EXPECT_TRUE(has(e, "the limit is 1000000 placed nodes")) << e;
    EXPECT_LT(seconds, 30.0);  // generous for a loaded machine: the walk it replaces never ended
    // Control: 2^8 paths place the quad 256 times.
    EXPECT_EQ(gltf_text_scene("dag.gltf", doubling_chain(8).embedded()).placed_triangle_count(), 512u);
    // The limit is the load's to set (LoadOptions::max_placed_nodes).
    MemoryFiles f;
    f.files["dag.gltf"] = doubling_chain(8).embedded();
    LoadOptions small = f.options();
    small.max_placed_nodes = 100;
    const std::string e100 = error_of([&] { (void)gltf_scene("dag.gltf", small); });
    EXPECT_TRUE(has(e100, "places more than 100 nodes")) << e100;
    // Without scenes, the roots (nodes that are no other's child) are counted the same way.
    GltfBuilder g = doubling_chain(40);
    g.doc.erase("scenes");
    g.doc.erase("scene");
    EXPECT_TRUE(has(gltf_text_error("dag.gltf", g.embedded()), "dag.gltf: nodes: the node hierarchy places more than 1000000"));
}

TEST(GltfDocument, CyclesAndRootlessHierarchiesAreNamed) {
    GltfBuilder g = quad_model();
    g.doc["nodes"] = {{{"children", {1}}}, {{"children", {2}}, {"mesh", 0}}, {{"children", {1}}}};
    EXPECT_TRUE(has(gltf_text_error("c.gltf", g.embedded()), "c.gltf: nodes[1]: the node is its own ancestor (a cycle)"));
    g.doc.erase("scenes");
    g.doc.erase("scene");
    g.doc["nodes"] = {{{"children", {1}}, {"mesh", 0}}, {{"children", {0}}}};
    EXPECT_TRUE(has(gltf_text_error("c.gltf", g.embedded()), "c.gltf: nodes: every node is another's child"));
    // Control: a shared child without a cycle is placed once per path.
    g.doc["nodes"] = {{{"children", {1, 2}}}, {{"children", {3}}}, {{"children", {3}}}, {{"mesh", 0}}};
    EXPECT_EQ(gltf_text_scene("c.gltf", g.embedded()).placed_triangle_count(), 4u);
}

TEST(GltfDocument, GlbHeaderVersionMustBeTwo) {
    const std::string glb = quad_model().glb();
    EXPECT_TRUE(has(gltf_text_error("v3.glb", glb_with_version(glb, 3)), "v3.glb: GLB header: version 3 is not supported"));
    EXPECT_TRUE(has(gltf_text_error("v1.glb", glb_with_version(glb, 1)), "v1.glb: glTF 1.0 is not supported"));
    std::string longer = glb + "pad!";
    EXPECT_TRUE(has(gltf_text_error("l.glb", longer), "l.glb: GLB header: length ")) << gltf_text_error("l.glb", longer);
    EXPECT_EQ(gltf_text_scene("v2.glb", glb).triangle_count(), 2u);
}

TEST(GltfDocument, AssetVersionMustBeTwo) {
    GltfBuilder g = quad_model();
    g.doc["asset"]["version"] = "3.0";
    EXPECT_TRUE(has(gltf_text_error("a.gltf", g.embedded()), "a.gltf: asset.version: '3.0' is not supported"));
    g.doc["asset"]["version"] = "two";
    EXPECT_TRUE(has(gltf_text_error("a.gltf", g.embedded()), "a.gltf: asset.version: 'two' is not supported"));
    g.doc["asset"] = {{"generator", "x"}};
    EXPECT_TRUE(has(gltf_text_error("a.gltf", g.embedded()), "a.gltf: asset.version: required, but missing"));
    g.doc["asset"] = {{"version", "2.0"}, {"minVersion", "2.1"}};
    EXPECT_TRUE(has(gltf_text_error("a.gltf", g.embedded()), "a.gltf: asset.minVersion: '2.1' is not supported"));
    // Control: a later 2.x minor version is read as 2.0 (the specification's promise).
    g.doc["asset"] = {{"version", "2.1"}};
    EXPECT_EQ(gltf_text_scene("a.gltf", g.embedded()).triangle_count(), 2u);
}

TEST(GltfDocument, DefaultSceneMustExist) {
    GltfBuilder g = quad_model();
    g.doc["scenes"] = json::array();
    g.doc["scene"] = 0;
    EXPECT_TRUE(has(gltf_text_error("s.gltf", g.embedded()), "s.gltf: scene: scene 0 does not exist (the file has 0)"));
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 1;
    EXPECT_TRUE(has(gltf_text_error("s.gltf", g.embedded()), "s.gltf: scene: scene 1 does not exist (the file has 1)"));
    g.doc["scene"] = 0;
    EXPECT_EQ(gltf_text_scene("s.gltf", g.embedded()).triangle_count(), 2u);
}

TEST(GltfDocument, FieldsOfTheWrongTypeOrRangeAreNamed) {
    struct Case {
        std::function<void(json&)> breakit;
        const char* expect;
    };
    const json perspective = {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}};
    const std::vector<Case> cases = {
        {[&](json& d) { d["cameras"] = {perspective}; d["cameras"][0]["perspective"]["aspectRatio"] = 0; },
         "cameras[0].perspective.aspectRatio: 0 is out of range (must be above 0)"},
        {[&](json& d) { d["cameras"] = {perspective}; d["cameras"][0]["perspective"]["aspectRatio"] = -1.5; },
         "cameras[0].perspective.aspectRatio: -1.5 is out of range (must be above 0)"},
        {[&](json& d) { d["cameras"] = {perspective}; d["cameras"][0]["perspective"]["yfov"] = 4; },
         "cameras[0].perspective.yfov: 4 is out of range"},
        {[&](json& d) { d["cameras"] = {perspective}; d["cameras"][0]["perspective"].erase("znear"); },
         "cameras[0].perspective.znear: required, but missing"},
        {[](json& d) { d["cameras"] = {{{"type", "fisheye"}}}; }, "cameras[0].type: 'fisheye' is not one of perspective, orthographic"},
        {[](json& d) {
             d["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}};
         },
         "cameras[0].orthographic.xmag: must not be zero"},
        {[](json& d) {
             d["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", "bright"}}};
         },
         "extensions.KHR_lights_punctual.lights[0].intensity: expected a number, got a string (\"bright\")"},
        {[](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "laser"}}}; },
         "extensions.KHR_lights_punctual.lights[0].type: 'laser' is not one of point, spot, directional"},
        {[](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"color", {1, 1}}}}; },
         "extensions.KHR_lights_punctual.lights[0].color: expected 3 numbers, got 2"},
        {[](json& d) { d["nodes"][0]["translation"] = "up"; }, "nodes[0].translation: expected an array, got a string"},
        {[](json& d) { d["nodes"][0]["scale"] = {1, 1}; }, "nodes[0].scale: expected 3 numbers, got 2"},
        {[](json& d) { d["nodes"][0]["mesh"] = 1.5; }, "nodes[0].mesh: expected a whole number, got a number (1.5)"},
        {[](json& d) { d["nodes"][0]["children"] = {4}; }, "nodes[0].children[0]: node 4 does not exist (the file has 1)"},
        {[](json& d) { d["accessors"][0]["count"] = "4"; }, "accessors[0].count: expected a whole number, got a string"},
        {[](json& d) { d["accessors"][0]["componentType"] = 5124; }, "accessors[0].componentType: 5124 is not a glTF component type"},
        {[](json& d) { d["accessors"][0]["type"] = "VEC5"; }, "accessors[0].type: 'VEC5' is not one of SCALAR"},
        {[](json& d) { d["bufferViews"][0]["byteStride"] = 2; }, "bufferViews[0].byteStride: 2 is out of range (must be from 4 to 252)"},
        {[](json& d) { d["materials"] = {{{"doubleSided", "yes"}}}; }, "materials[0].doubleSided: expected true or false"},
        {[](json& d) { d["materials"] = {{{"emissiveFactor", {1, "x", 1}}}}; },
         "materials[0].emissiveFactor[1]: expected a number, got a string"},
        {[](json& d) { d["skins"] = {{{"joints", json::array()}}}; }, "skins[0].joints: a skin needs at least one joint"},
        {[](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 9; }, "meshes[0].primitives[0].mode: 9 is out of range"},
        {[](json& d) { d["extensionsUsed"] = {"KHR_lights_punctual", 7}; }, "extensionsUsed[1]: expected a name, got a number"},
    };
    for (const Case& c : cases) {
        GltfBuilder g = quad_model();
        c.breakit(g.doc);
        const std::string e = gltf_text_error("bad/f.gltf", g.embedded());
        EXPECT_EQ(e.rfind("bad/f.gltf: ", 0), 0u) << e;
        EXPECT_TRUE(has(e, c.expect)) << "want: " << c.expect << "\ngot:  " << e;
        // The same document as a .glb is checked the same way.
        const std::string eb = gltf_text_error("bad/f.glb", g.glb());
        EXPECT_TRUE(has(eb, c.expect)) << "want: " << c.expect << "\ngot:  " << eb;
    }
    // Control: valid values of the same fields load.
    GltfBuilder g = quad_model();
    g.doc["cameras"] = {perspective};
    g.doc["cameras"][0]["perspective"]["aspectRatio"] = 1.5;
    g.doc["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
    g.doc["scenes"][0]["nodes"].push_back(1);
    g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    g.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 2}, {"color", {1, 1, 1}}}};
    g.doc["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    g.doc["materials"] = {{{"doubleSided", true}, {"emissiveFactor", {0, 0, 0}}}};
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const Scene s = gltf_text_scene("ok.gltf", g.embedded());
    EXPECT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.camera.height, 427);  // 640 / 1.5
}

}  // namespace
