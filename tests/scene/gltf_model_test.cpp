// glTF loading: every kind of file and primitive the loader accepts, and each
// malformed case with the glTF path its message must name.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gltf_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_scene.hpp"
#include "scene/load/scene_file.hpp"
#include "scene/load/scene_loader.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {

struct Files : MemoryFiles {
    LoadOptions opts() const {
        LoadOptions o = options();
        o.decode_texture = fake_rgba_decode;
        // The file's own triangles only: presentation_test.cpp covers the ground.
        o.presentation.ground = false;
        return o;
    }
    Scene load(const std::string& file) const { return gltf_scene(file, opts()); }
    std::string error(const std::string& file) const {
        return error_of([&] { (void)gltf_scene(file, opts()); });
    }
};

Files with(const std::string& name, const std::string& text) {
    Files f;
    f.files[name] = text;
    return f;
}

void expect_near(glm::vec3 a, glm::vec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(Gltf, EmbeddedQuadLoadsWithNormalsAndTexcoords) {
    const Scene s = with("m/quad.gltf", quad_model().embedded()).load("m/quad.gltf");
    ASSERT_EQ(s.triangle_count(), 2u);
    ASSERT_EQ(s.normals.size(), 6u);
    ASSERT_EQ(s.uvs.size(), 6u);
    expect_near(s.vertices[1], {1, 0, 0});
    expect_near(s.normals[0], {0, 0, 1});
    EXPECT_EQ(s.uvs[2], glm::vec2(1, 0));
    // No material: the specification's default, a white rough metal.
    const SceneMaterial& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(m.kind, CLP_MAT_GLTF);
    EXPECT_EQ(m.metallic, 1.0f);
    EXPECT_EQ(m.roughness, 1.0f);
    EXPECT_GT(s.environment.color.x, 0.0f);  // nothing emits: lit by the presentation's sky
}

TEST(Gltf, ExternalBufferAndGlbGiveTheSameTriangles) {
    const GltfBuilder g = quad_model();
    Files f;
    f.files["m/quad.gltf"] = g.external("quad%20data.bin");
    f.files["m/quad data.bin"] = g.bin;
    f.files["m/quad.glb"] = g.glb();
    const Scene a = f.load("m/quad.gltf"), b = f.load("m/quad.glb");
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    for (std::size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
}

// Buffer data URIs are decoded by the loader (gltf_data_uris.cpp), not by
// tinygltf: the same triangles as the .glb, whatever the JSON writer did with
// "/" (escaped "\/" is valid JSON and left to tinygltf), and a wrong
// byteLength or bad base64 still fails with the buffer named.
TEST(Gltf, DataUriBuffersGiveTheSameTrianglesAsGlb) {
    GltfBuilder g = quad_model();
    g.bin += std::string("\xff\xfe\xfd", 3);  // base64 with '/' and '+' in it, and padding
    const std::string embedded = g.embedded();
    ASSERT_NE(embedded.find('/', embedded.find("base64,")), std::string::npos);
    std::string escaped;
    for (char c : embedded) escaped += c == '/' ? std::string("\\/") : std::string(1, c);
    Files f;
    f.files["m/e.gltf"] = embedded;
    f.files["m/x.gltf"] = escaped;
    f.files["m/quad.glb"] = g.glb();
    const Scene a = f.load("m/e.gltf"), b = f.load("m/x.gltf"), c = f.load("m/quad.glb");
    ASSERT_EQ(a.vertices.size(), c.vertices.size());
    ASSERT_EQ(b.vertices.size(), c.vertices.size());
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
        EXPECT_EQ(a.vertices[i], c.vertices[i]);
        EXPECT_EQ(b.vertices[i], c.vertices[i]);
        EXPECT_EQ(a.uvs[i], c.uvs[i]);
    }
    nlohmann::json wrong = nlohmann::json::parse(embedded);
    wrong["buffers"][0]["byteLength"] = g.bin.size() + 4;
    const std::string e1 = with("w.gltf", wrong.dump()).error("w.gltf");
    EXPECT_NE(e1.find("w.gltf: not a valid glTF 2.0 file"), std::string::npos) << e1;
    wrong["buffers"][0]["byteLength"] = g.bin.size();
    wrong["buffers"][0]["uri"] = "data:application/octet-stream;base64,@@@@";
    const std::string e2 = with("w.gltf", wrong.dump()).error("w.gltf");
    EXPECT_NE(e2.find("w.gltf: not a valid glTF 2.0 file"), std::string::npos) << e2;
}

TEST(Gltf, NodeHierarchyComposesTrsAndMatrices) {
    GltfBuilder g = quad_model();
    // Parent: translate (10, 0, 0), rotate 90 degrees about z, scale 2; child: a matrix moving +1 in y.
    const float h = std::sqrt(0.5f);
    g.doc["nodes"] = {{{"translation", {10, 0, 0}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}, {"children", {1}}},
                      {{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1}}}};
    const Scene s = with("q.gltf", g.embedded()).load("q.gltf");
    ASSERT_EQ(s.triangle_count(), 2u);
    // Vertex (1, 0, 0): child -> (1, 1, 0); scale -> (2, 2, 0); rotate -> (-2, 2, 0); translate -> (8, 2, 0).
    expect_near(s.vertices[1], {8, 2, 0});
    expect_near(s.vertices[0], {8, 0, 0});
    expect_near(s.normals[0], {0, 0, 1});
}

TEST(Gltf, MeshPlacedTwiceGivesTwoObjects) {
    GltfBuilder g = quad_model();
    g.doc["nodes"] = {{{"mesh", 0}}, {{"mesh", 0}, {"translation", {0, 0, 5}}}};
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    // Stored once and placed by two instances; flattened, two objects.
    const Scene inst = with("q.gltf", g.embedded()).load("q.gltf");
    ASSERT_EQ(inst.instances.size(), 2u);
    const Scene s = flatten_instances(inst);
    ASSERT_EQ(s.triangle_count(), 4u);
    EXPECT_NE(s.triangle_object[0], s.triangle_object[2]);
    expect_near(s.vertices[6], {0, 0, 5});
}

TEST(Gltf, StripsFansAndUnindexedPrimitivesBecomeTriangles) {
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3);  // a zigzag, for the strip
    const int ring = g.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);  // around the square, for the fan
    g.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"mode", 5}},   // strip: 2 triangles
                                        {{"attributes", {{"POSITION", ring}}}, {"mode", 6}},  // fan: 2 triangles
                                        {{"attributes", {{"POSITION", pos}}}, {"mode", 4}}}}}};  // 4 corners: not whole
    g.doc["nodes"] = {{{"mesh", 0}}};
    // The incomplete triangle is dropped with a warning (gltf_support_test.cpp).
    const Scene five = with("s.gltf", g.embedded()).load("s.gltf");
    EXPECT_EQ(five.triangle_count(), 5u);
    ASSERT_EQ(five.warnings.size(), 1u);
    EXPECT_NE(five.warnings[0].find("meshes[0].primitives[2]: 4 corners"), std::string::npos);
    g.doc["meshes"][0]["primitives"].erase(2);
    const Scene s = with("s.gltf", g.embedded()).load("s.gltf");
    ASSERT_EQ(s.triangle_count(), 4u);
    // Every strip and fan triangle faces +z, as its first one does.
    for (std::size_t t = 0; t < 4; ++t)
        EXPECT_GT(glm::cross(s.vertices[3 * t + 1] - s.vertices[3 * t], s.vertices[3 * t + 2] - s.vertices[3 * t]).z, 0) << t;
}

TEST(Gltf, PointsAndLinesAloneAreRefused) {
    for (int mode : {0, 1, 2, 3}) {
        GltfBuilder g = quad_model();
        g.doc["meshes"][0]["primitives"][0]["mode"] = mode;
        const std::string e = with("p.gltf", g.embedded()).error("p.gltf");
        EXPECT_NE(e.find("p.gltf: meshes[0].primitives[0].mode: points and lines cannot be rendered"), std::string::npos) << e;
    }
}

TEST(Gltf, MalformedFilesNameTheGltfPath) {
    struct Case {
        const char* what;
        std::function<void(GltfBuilder&)> breakit;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {"accessor out of range", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 99; },
         "meshes[0].primitives[0].attributes.TEXCOORD_0: accessor 99 does not exist"},
        {"accessor past its view", [](GltfBuilder& g) { g.doc["accessors"][2]["count"] = 40; },
         "meshes[0].primitives[0].attributes.TEXCOORD_0 (accessors[2]): 40 elements from byte 0 run past the end"},
        {"view past its buffer", [](GltfBuilder& g) { g.doc["bufferViews"][0]["byteLength"] = 100000; },
         "bufferViews[0]"},
        {"index out of range", [](GltfBuilder& g) { g.doc["accessors"][3]["bufferView"] = 2; },  // uv floats read as indices
         "meshes[0].primitives[0].indices: index"},
        {"wrong accessor type", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2; },
         "meshes[0].primitives[0].attributes.NORMAL (accessors[2]): expected VEC3, found VEC2"},
        {"count mismatch", [](GltfBuilder& g) { g.doc["accessors"][1]["count"] = 3; },
         "meshes[0].primitives[0].attributes.NORMAL: 3 elements, but POSITION has 4"},
        {"missing material", [](GltfBuilder& g) { g.doc["meshes"][0]["primitives"][0]["material"] = 3; },
         "meshes[0].primitives[0].material: material 3 does not exist"},
        {"missing mesh", [](GltfBuilder& g) { g.doc["nodes"][0]["mesh"] = 7; }, "nodes[0].mesh: mesh 7 does not exist"},
        {"node cycle", [](GltfBuilder& g) { g.doc["nodes"][0]["children"] = {0}; }, "nodes[0]: the node is its own ancestor"},
        {"sparse accessor",
         [](GltfBuilder& g) {
             g.doc["accessors"][0]["sparse"] = {{"count", 1},
                                               {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                               {"values", {{"bufferView", 0}}}};
         },
         "sparse accessors are not supported"},
        {"texture out of range",
         [](GltfBuilder& g) { g.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 4}}}}}}}; },
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: texture 4 does not exist"},
        {"bad alpha mode", [](GltfBuilder& g) { g.doc["materials"] = {{{"alphaMode", "SOMETIMES"}}}; },
         "materials[0].alphaMode: unknown alpha mode 'SOMETIMES'"},
        {"base colour out of range",
         [](GltfBuilder& g) { g.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 2, 1, 1}}}}}}; },
         "materials[0].pbrMetallicRoughness.baseColorFactor[1]: must be in"},
    };
    for (const Case& c : cases) {
        GltfBuilder g = quad_model();
        c.breakit(g);
        const std::string e = with("bad/x.gltf", g.embedded()).error("bad/x.gltf");
        EXPECT_EQ(e.rfind("bad/x.gltf: ", 0), 0u) << c.what << ": " << e;
        EXPECT_NE(e.find(c.expect), std::string::npos) << c.what << ": " << e;
    }
}

TEST(Gltf, MissingFilesAndBadUrisNameTheirEntry) {
    const GltfBuilder g = quad_model();
    EXPECT_NE(with("m/q.gltf", g.external("gone.bin")).error("m/q.gltf").find("m/q.gltf: buffers[0].uri: m/gone.bin: no such file"),
              std::string::npos);
    EXPECT_NE(with("m/q.gltf", g.external("http://example.org/q.bin")).error("m/q.gltf").find("buffers[0].uri: 'http://"),
              std::string::npos);
    EXPECT_NE(with("m/q.gltf", g.external("data:application/octet-stream,abc")).error("m/q.gltf").find("must be base64"),
              std::string::npos);
    EXPECT_NE(with("m/q.gltf", g.external("bad%zzname.bin")).error("m/q.gltf").find("bad %-escape"), std::string::npos);
    json d = json::parse(g.embedded());
    // A missing image is not fatal (its textures are left out, as Blender does), but named with its resolved path.
    d["images"] = {{{"uri", "missing.png"}}};
    const Scene missing = with("m/q.gltf", d.dump()).load("m/q.gltf");
    bool named = false;
    for (const auto& w : missing.warnings) named = named || w.find("m/q.gltf: images[0].uri: m/missing.png: no such file") == 0;
    EXPECT_TRUE(named);
    EXPECT_NE(with("m/q.gltf", "{\"asset\": ").error("m/q.gltf").find("m/q.gltf: not a valid glTF 2.0 file"), std::string::npos);
    EXPECT_NE(with("m/q.gltf", "{}").error("m/q.gltf").find("m/q.gltf: "), std::string::npos);
}

json textured_material(int alpha_mode_index = 0) {
    static const char* modes[] = {"OPAQUE", "MASK", "BLEND"};
    return {{{"pbrMetallicRoughness",
              {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.5},
               {"baseColorFactor", {0.5, 1, 1, 0.75}}}},
             {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
             {"emissiveFactor", {1, 0.5, 0}},
             {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}},
             {"alphaMode", modes[alpha_mode_index]},
             {"alphaCutoff", 0.25},
             {"doubleSided", true},
             {"name", "painted"}}};
}

TEST(Gltf, MaterialsTexturesAndSamplers) {
    GltfBuilder g = quad_model();
    g.doc["materials"] = textured_material(1);
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    // A 2x1 texture: red, then half-transparent green.
    const std::string texels = std::string("RGBA\x02\x01", 6) + std::string("\xff\x00\x00\xff\x00\xff\x00\x80", 8);
    g.doc["images"] = {{{"uri", "data:image/png;base64," + base64(texels)}}};
    g.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}};
    g.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
    const Scene s = with("t.gltf", g.embedded()).load("t.gltf");
    const SceneMaterial& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(s.material_names[s.triangle_material[0]], "t.gltf:painted");
    EXPECT_EQ(m.kind, CLP_MAT_GLTF);
    EXPECT_FLOAT_EQ(m.albedo[0], 0.5f);
    EXPECT_FLOAT_EQ(m.alpha, 0.75f);
    EXPECT_FLOAT_EQ(m.metallic, 0.25f);
    EXPECT_FLOAT_EQ(m.roughness, 0.5f);
    EXPECT_FLOAT_EQ(m.emission[0], 4.0f);  // emissiveFactor x emissiveStrength
    EXPECT_FLOAT_EQ(m.emission[1], 2.0f);
    EXPECT_EQ(m.alpha_mode, CLP_ALPHA_MASK);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.25f);
    EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
    EXPECT_TRUE(m.flags & CLP_MATF_TWO_SIDED_EMISSION);
    // One image with one sampler: one texture, shared by both slots.
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(m.texture[CLP_TEX_BASE], 0);
    EXPECT_EQ(m.texture[CLP_TEX_NORMAL], 0);
    EXPECT_EQ(m.texture[CLP_TEX_MR], CLP_NO_TEXTURE);
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.rgba8[7], 0x80);
    EXPECT_EQ(t.wrap_s, CLP_WRAP_CLAMP);
    EXPECT_EQ(t.wrap_t, CLP_WRAP_MIRROR);
    EXPECT_TRUE(t.nearest);
    EXPECT_FALSE(s.environment.emits());  // the emissive material lights the scene
}

TEST(Gltf, UndecodableTextureNamesImageAndUse) {
    GltfBuilder g = quad_model();
    g.doc["materials"] = textured_material();
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    g.doc["images"] = {{{"uri", "data:image/png;base64," + base64("not a png at all")}}};
    g.doc["textures"] = {{{"source", 0}}};
    Files f = with("t.gltf", g.embedded());
    // Through the real decoder (OpenImageIO) too.
    for (bool real : {false, true}) {
        LoadOptions o = f.opts();
        if (real) o.decode_texture = decode_texture;
        const std::string e = error_of([&] { (void)gltf_scene("t.gltf", o); });
        EXPECT_NE(e.find("t.gltf: images[0] (used by materials[0].pbrMetallicRoughness.baseColorTexture): "), std::string::npos) << e;
        EXPECT_NE(e.find("cannot decode the image"), std::string::npos) << e;
    }
}

TEST(Gltf, VertexColoursAndTangents) {
    GltfBuilder g = quad_model();
    const int col = g.accessor(std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0},
                               5121, "VEC4", 4);
    g.doc["accessors"][col]["normalized"] = true;
    const int tan = g.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, -1, 1, 0, 0, 1}, "VEC4", 4);
    g.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = col;
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = tan;
    g.doc["nodes"][0]["scale"] = {-1, 1, 1};  // a mirror: winding and bitangent sign flip
    const Scene s = with("c.gltf", g.embedded()).load("c.gltf");
    ASSERT_EQ(s.colors.size(), 6u);
    ASSERT_EQ(s.tangents.size(), 6u);
    // Triangle (0, 1, 2) is stored as (0, 2, 1) after the mirror.
    EXPECT_EQ(s.colors[0], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(s.colors[1], glm::vec4(0, 0, 1, 1));
    EXPECT_EQ(s.tangents[0], glm::vec4(-1, 0, 0, -1));
    EXPECT_EQ(s.tangents[1], glm::vec4(-1, 0, 0, 1));  // corner 2 had w = -1
    // The mirrored quad still faces +z through its stored winding and normals.
    EXPECT_GT(glm::cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]).z, 0);
    expect_near(s.normals[0], {0, 0, 1});
}

TEST(Gltf, CamerasByDefaultNameAndIndex) {
    GltfBuilder g = quad_model();
    g.doc["cameras"] = {{{"type", "perspective"}, {"name", "wide"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}},
                        {{"type", "perspective"}, {"name", "tall"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"aspectRatio", 2.0}}}}};
    g.doc["nodes"].push_back({{"camera", 0}, {"translation", {0.5, 0.5, 3}}});
    g.doc["nodes"].push_back({{"camera", 1}, {"translation", {0, 0, 7}}});
    g.doc["scenes"][0]["nodes"] = {0, 1, 2};
    Files f = with("c.gltf", g.embedded());
    Scene s = f.load("c.gltf");
    expect_near(s.camera.eye, {0.5f, 0.5f, 3});
    expect_near(s.camera.target, {0.5f, 0.5f, 2});
    EXPECT_NEAR(s.camera.vfov_degrees, 57.29578f, 1e-3f);
    EXPECT_FALSE(s.camera.has_lens()) << "glTF has no thin lens: a pinhole unless --camera gives an aperture";
    for (const char* pick : {"tall", "1"}) {
        LoadOptions o = f.opts();
        o.gltf_camera = pick;
        s = gltf_scene("c.gltf", o);
        expect_near(s.camera.eye, {0, 0, 7});
        EXPECT_EQ(s.camera.height, 320);
    }
    LoadOptions o = f.opts();
    o.gltf_camera = "nope";
    EXPECT_NE(error_of([&] { (void)gltf_scene("c.gltf", o); }).find("c.gltf: no camera 'nope' placed by a node (cameras: 0 'wide', 1 'tall')"),
              std::string::npos);
    // Orthographic cameras render as such (gltf_real_files_test.cpp has the basis).
    g.doc["cameras"][0] = {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}};
    EXPECT_EQ(with("c.gltf", g.embedded()).load("c.gltf").camera.ortho_half_height, 1.0f);
}

TEST(Gltf, PunctualLights) {
    GltfBuilder g = quad_model();
    const float h = std::sqrt(0.5f);
    g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    g.doc["extensions"] = {{"KHR_lights_punctual",
                            {{"lights",
                              {{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 8}},
                               {{"type", "spot"}, {"intensity", 2}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
                               {{"type", "directional"}, {"intensity", 3}}}}}}};
    // Rotation -90 degrees about x: local -z becomes -y.
    json ext = {{"KHR_lights_punctual", {{"light", 0}}}};
    g.doc["nodes"].push_back({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    g.doc["nodes"].push_back({{"translation", {0, 5, 0}}, {"rotation", {-h, 0, 0, h}},
                              {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    g.doc["nodes"].push_back({{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    g.doc["scenes"][0]["nodes"] = {0, 1, 2, 3};
    const Scene s = with("l.gltf", g.embedded()).load("l.gltf");
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, PunctualLight::Type::Point);
    expect_near(s.lights[0].position, {1, 2, 3});
    expect_near(s.lights[0].intensity, {8, 4, 2});
    EXPECT_EQ(s.lights[1].type, PunctualLight::Type::Spot);
    expect_near(s.lights[1].direction, {0, -1, 0});
    EXPECT_NEAR(s.lights[1].spot_outer_degrees, 28.64789f, 1e-3f);
    EXPECT_EQ(s.lights[2].type, PunctualLight::Type::Directional);
    expect_near(s.lights[2].direction, {0, -1, 0});
    EXPECT_FALSE(s.environment.emits());
    g.doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 9;
    EXPECT_NE(with("l.gltf", g.embedded()).error("l.gltf").find("nodes[1].extensions.KHR_lights_punctual.light: light 9 does not exist"),
              std::string::npos);
}

TEST(Gltf, MeshObjectInASceneFile) {
    GltfBuilder g = quad_model();
    g.doc["materials"] = {{{"name", "paint"}}};
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    Files f = with("s/models/quad.gltf", g.embedded());
    f.files["s/scene.json"] = R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0]},
        "materials": {"lamp": {"type": "emitter", "emission": [1, 1, 1]}, "grey": {"type": "diffuse"}},
        "objects": [{"type": "plane", "material": "lamp"},
                    {"type": "mesh", "file": "models/quad.gltf", "transform": {"translate": [0, 0, 1]}},
                    {"type": "mesh", "file": "models/quad.gltf", "materials": {"paint": "grey"}}]})";
    const Scene s = parse_scene_file(f.files["s/scene.json"], "s/scene.json", f.opts());
    ASSERT_EQ(s.triangle_count(), 6u);
    expect_near(s.vertices[6], {0, 0, 1});
    EXPECT_EQ(s.material_names[s.triangle_material[2]], "s/models/quad.gltf:paint");
    EXPECT_EQ(s.material_names[s.triangle_material[4]], "grey");
    f.files["s/scene.json"] = R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "models/gone.glb"}]})";
    EXPECT_NE(error_of([&] { (void)parse_scene_file(f.files["s/scene.json"], "s/scene.json", f.opts()); })
                  .find("objects[0].file: s/models/gone.glb: no such file"),
              std::string::npos);
}

TEST(Gltf, SuzanneFromTheRepository) {
    const std::string file = scenes_dir() + "/suzanne/Suzanne.gltf";
    const Scene s = load_scene(file);
    EXPECT_EQ(s.triangle_count(), 3936u + 2u);  // and the presentation's ground
    EXPECT_EQ(s.tangents.size(), s.vertices.size());
    EXPECT_EQ(s.uvs.size(), s.vertices.size());
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.textures[0].width, 256);
    EXPECT_FALSE(s.textures[0].is_float);
    const SceneMaterial& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(m.kind, CLP_MAT_GLTF);
    EXPECT_EQ(m.texture[CLP_TEX_BASE], 0);
    EXPECT_EQ(m.texture[CLP_TEX_MR], 1);
}

}  // namespace
