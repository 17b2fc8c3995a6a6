// Compressed glTF meshes (KHR_draco_mesh_compression, EXT_meshopt_compression)
// load as the uncompressed file they were made from: exactly for meshopt's
// lossless codecs, within the quantisation step for Draco's quantised
// attributes and meshopt's octahedral filter. Broken or hostile compressed
// data is refused with the file and the glTF path, never a crash.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "gltf_compressed_files.hpp"
#include "memory_files.hpp"
#include "scene/load/gltf_model.hpp"

using namespace clpath;
using namespace clpath::test;
using nlohmann::json;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

GltfModel load(const std::string& name, const std::string& text, std::size_t max_triangles = 0) {
    MemoryFiles f;
    f.files[name] = text;
    LoadOptions o = f.options();
    if (max_triangles) o.max_triangles = max_triangles;
    return load_gltf(name, o);
}

std::string load_error(const std::string& name, const std::string& text, std::size_t max_triangles = 0) {
    return error_of([&] { (void)load(name, text, max_triangles); });
}

const GltfPrimitive& only_primitive(const GltfModel& m) {
    EXPECT_EQ(m.meshes.size(), 1u);
    EXPECT_EQ(m.meshes.at(0).size(), 1u);
    return m.meshes.at(0).at(0);
}

// Largest per-component differences between two loads of one mesh, corner by
// corner; with `rotations` each triangle of b may start at any of its corners
// (meshopt's triangle codec may rotate a triangle, keeping its winding), the
// rotation chosen by the positions.
struct Differences {
    float pos = 0, nrm = 0, uv = 0;
};
template <class V>
float max_diff(const V& a, const V& b) {
    float d = 0;
    for (int c = 0; c < V::length(); ++c) d = std::max(d, std::fabs(a[c] - b[c]));
    return d;
}
Differences differences(const GltfPrimitive& a, const GltfPrimitive& b, bool rotations = false) {
    Differences d;
    EXPECT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_EQ(a.normals.size(), b.normals.size());
    EXPECT_EQ(a.uvs.size(), b.uvs.size());
    if (a.vertices.size() != b.vertices.size() || a.normals.size() != a.vertices.size() || b.normals.size() != b.vertices.size())
        return {1e30f, 1e30f, 1e30f};
    for (std::size_t t = 0; t + 2 < a.vertices.size(); t += 3) {
        int best = 0;
        float best_d = 1e30f;
        for (int r = 0; r < (rotations ? 3 : 1); ++r) {
            float dr = 0;
            for (int k = 0; k < 3; ++k) dr = std::max(dr, max_diff(a.vertices[t + k], b.vertices[t + (k + r) % 3]));
            if (dr < best_d) best_d = dr, best = r;
        }
        for (int k = 0; k < 3; ++k) {
            const std::size_t i = t + std::size_t(k), j = t + std::size_t((k + best) % 3);
            d.pos = std::max(d.pos, max_diff(a.vertices[i], b.vertices[j]));
            d.nrm = std::max(d.nrm, max_diff(a.normals[i], b.normals[j]));
            if (!a.uvs.empty() && a.uvs.size() == b.uvs.size()) d.uv = std::max(d.uv, max_diff(a.uvs[i], b.uvs[j]));
        }
    }
    return d;
}

}  // namespace

TEST(GltfCompressed, MeshoptLosslessEqualsTheOriginalExactly) {
    const TestMesh mesh = bumpy_grid(12, false);
    const GltfModel plain = load("plain.gltf", plain_file(mesh).gltf());
    ASSERT_EQ(only_primitive(plain).vertices.size(), mesh.idx.size());
    for (const char* mode : {"TRIANGLES", "INDICES"})
        for (bool marked : {true, false}) {
            MeshoptChoice c;
            c.index_mode = mode;
            c.mark_fallback = marked;
            const TestFile f = meshopt_file(mesh, c);
            for (const auto& [name, text] : {std::pair<std::string, std::string>{"m.gltf", f.gltf()}, {"m.glb", f.glb()}}) {
                SCOPED_TRACE(name + " " + mode + (marked ? " marked" : " unmarked"));
                const GltfModel m = load(name, text);
                EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
                // INDICES keeps every index as it was; TRIANGLES may rotate a triangle's corners.
                const Differences d = differences(only_primitive(plain), only_primitive(m), std::string(mode) == "TRIANGLES");
                EXPECT_EQ(d.pos, 0.0f);
                EXPECT_EQ(d.nrm, 0.0f);
                EXPECT_EQ(d.uv, 0.0f);
                if (std::string(mode) == "INDICES") {
                    EXPECT_EQ(only_primitive(m).vertices, only_primitive(plain).vertices);
                    EXPECT_EQ(only_primitive(m).normals, only_primitive(plain).normals);
                    EXPECT_EQ(only_primitive(m).uvs, only_primitive(plain).uvs);
                }
            }
        }
}

// OCTAHEDRAL with 16 bits: the decoder maps (u, v), each within half a step
// h = 0.5 / 32767 of the encoded value, to (u, v, 1 - |u| - |v|) (or its
// fold, which moves no coordinate further), a vector of L1 norm 1 and so of
// length at least 1/sqrt(3), and normalises it. The unnormalised vector moves
// by at most |(h, h, 2h)| = sqrt(6) h; normalising moves the unit vector by at
// most 2 sqrt(3) times that: 6 sqrt(2) h < 8.5 h. The decoder then rounds to
// 16-bit snorm (another h) and the loader divides by 32767: 9.5 h in all.
TEST(GltfCompressed, MeshoptOctahedralNormalsWithinTheirQuantisation) {
    const TestMesh mesh = bumpy_grid(12, false);
    const GltfModel plain = load("plain.gltf", plain_file(mesh).gltf());
    MeshoptChoice c;
    c.octahedral_normals = true;
    const GltfModel m = load("oct.glb", meshopt_file(mesh, c).glb());
    const Differences d = differences(only_primitive(plain), only_primitive(m), true);
    EXPECT_EQ(d.pos, 0.0f);
    EXPECT_EQ(d.uv, 0.0f);
    const float h = 0.5f / 32767.0f;
    EXPECT_LE(d.nrm, 9.5f * h);
    EXPECT_GT(d.nrm, 0.0f);  // the normals did go through the filter (16-bit storage is not float's)
}

// Draco quantises an attribute on a grid of step range / (2^bits - 1), range
// the largest extent over its components, and rounds to the nearest point:
// within half a step, plus float rounding of the dequantisation (bounded here
// by 4 ulp of the largest magnitude, 1 for the sheet and the unit square).
TEST(GltfCompressed, DracoWithinItsQuantisationStep) {
    const TestMesh mesh = bumpy_grid(12, false);
    const GltfModel plain = load("plain.gltf", plain_file(mesh).gltf());
    const float ulp4 = 4 * std::numeric_limits<float>::epsilon();
    float range = 0;
    for (int c = 0; c < 3; ++c) {
        float lo = 1e30f, hi = -1e30f;
        for (std::size_t i = c; i < mesh.pos.size(); i += 3) lo = std::min(lo, mesh.pos[i]), hi = std::max(hi, mesh.pos[i]);
        range = std::max(range, hi - lo);
    }
    for (int bits : {14, 8}) {
        DracoChoice c;
        c.position_bits = bits;
        const TestFile f = draco_file(mesh, c);
        for (const auto& [name, text] : {std::pair<std::string, std::string>{"d.gltf", f.gltf()}, {"d.glb", f.glb()}}) {
            SCOPED_TRACE(name + " " + std::to_string(bits) + " bits");
            const GltfModel m = load(name, text);
            const Differences d = differences(only_primitive(plain), only_primitive(m));
            EXPECT_LE(d.pos, 0.5f * range / float((1 << bits) - 1) + ulp4);
            EXPECT_LE(d.uv, 0.5f / float((1 << 12) - 1) + ulp4);
            EXPECT_EQ(d.nrm, 0.0f);  // normals were not quantised: Draco stores them as they are
            if (bits == 8) {  // control: 8 bits are visibly coarser than the 14-bit bound
                EXPECT_GT(d.pos, 0.5f * range / float((1 << 14) - 1) + ulp4);
            }
        }
    }
}

// The accessors say what the decoded values become: normals as 16-bit snorm,
// texture coordinates as 16-bit unorm (KHR_mesh_quantization), each rounded
// to the nearest step: within half a step of 1/32767 or 1/65535 (after
// Draco's 12-bit quantisation of the coordinates).
TEST(GltfCompressed, DracoValuesTakeTheirAccessorsComponentType) {
    const TestMesh mesh = bumpy_grid(12, false);
    const GltfModel plain = load("plain.gltf", plain_file(mesh).gltf());
    TestFile f = draco_file(mesh);
    const json& attrs = f.doc["meshes"][0]["primitives"][0]["attributes"];
    f.doc["accessors"][attrs["NORMAL"].get<int>()]["componentType"] = kGltfShort;
    f.doc["accessors"][attrs["NORMAL"].get<int>()]["normalized"] = true;
    f.doc["accessors"][attrs["TEXCOORD_0"].get<int>()]["componentType"] = 5123;
    f.doc["accessors"][attrs["TEXCOORD_0"].get<int>()]["normalized"] = true;
    f.require("KHR_mesh_quantization");
    const Differences d = differences(only_primitive(plain), only_primitive(load("q.glb", f.glb())));
    const float ulp4 = 4 * std::numeric_limits<float>::epsilon();
    EXPECT_LE(d.nrm, 0.5f / 32767 + ulp4);
    EXPECT_GT(d.nrm, 0.0f);  // control: they did go through 16 bits
    EXPECT_LE(d.uv, 0.5f / 4095 + 0.5f / 65535 + ulp4);
    // A value the component type cannot hold is an error naming the attribute.
    f.doc["accessors"][attrs["NORMAL"].get<int>()]["componentType"] = 5123;  // unsigned: no negative components
    const std::string e = load_error("q.glb", f.glb());
    EXPECT_TRUE(has(e, "q.glb: meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.NORMAL: a "
                       "decoded value does not fit accessors[1]'s component type 5123 (normalized)")) << e;
}

// On the grid Draco quantises to (whole numbers, range 2^11 - 1, 11 bits) it is exact.
TEST(GltfCompressed, DracoOnItsGridIsExact) {
    const TestMesh mesh = bumpy_grid(12, true);
    DracoChoice c;
    c.position_bits = 11;
    const GltfModel plain = load("plain.gltf", plain_file(mesh, false).gltf());
    const GltfModel m = load("d.glb", draco_file(mesh, c, false).glb());
    EXPECT_EQ(only_primitive(m).vertices, only_primitive(plain).vertices);
    EXPECT_EQ(only_primitive(m).normals, only_primitive(plain).normals);
}

// Edgebreaker reorders points and triangles: the same triangles, as a set.
TEST(GltfCompressed, DracoEdgebreakerKeepsTheTriangles) {
    const TestMesh mesh = bumpy_grid(12, true);
    DracoChoice c;
    c.position_bits = 11;
    c.sequential = false;
    const GltfPrimitive plain = only_primitive(load("plain.gltf", plain_file(mesh, false).gltf()));
    const GltfPrimitive m = only_primitive(load("d.glb", draco_file(mesh, c, false).glb()));
    ASSERT_EQ(m.vertices.size(), plain.vertices.size());
    // Each triangle by its corners, rotated to start at its least corner (winding kept).
    auto triangles = [](const std::vector<glm::vec3>& v) {
        std::vector<std::array<float, 9>> t;
        for (std::size_t i = 0; i + 2 < v.size(); i += 3) {
            auto key = [](glm::vec3 p) { return std::array<float, 3>{p.x, p.y, p.z}; };
            int first = 0;
            for (int k = 1; k < 3; ++k)
                if (key(v[i + std::size_t(k)]) < key(v[i + std::size_t(first)])) first = k;
            std::array<float, 9> a;
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) a[std::size_t(3 * k + c)] = v[i + std::size_t((first + k) % 3)][c];
            t.push_back(a);
        }
        std::sort(t.begin(), t.end());
        return t;
    };
    EXPECT_EQ(triangles(m.vertices), triangles(plain.vertices));
}

TEST(GltfCompressed, BrokenDracoDataIsAnErrorNamingThePrimitive) {
    const TestMesh mesh = bumpy_grid(6, false);
    const TestFile good = draco_file(mesh);
    const std::string at = "d.gltf: meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    // Truncated: the view keeps its first half.
    TestFile cut = good;
    cut.doc["bufferViews"][0]["byteLength"] = cut.doc["bufferViews"][0]["byteLength"].get<std::size_t>() / 2;
    std::string e = load_error("d.gltf", cut.gltf());
    EXPECT_TRUE(has(e, at + " (bufferViews[0], ")) << e;
    EXPECT_TRUE(has(e, "cannot be decoded")) << e;
    // Not Draco data at all.
    TestFile junk = good;
    std::fill(junk.bin.begin(), junk.bin.end(), 'x');
    e = load_error("d.gltf", junk.gltf());
    EXPECT_TRUE(has(e, at) && has(e, "not Draco data")) << e;
    // An attribute id the data does not have, a view that does not exist, a count that differs.
    TestFile bad_id = good;
    bad_id.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
    e = load_error("d.gltf", bad_id.gltf());
    EXPECT_TRUE(has(e, at + ".attributes.NORMAL: the Draco data has no attribute with id 9")) << e;
    TestFile bad_view = good;
    bad_view.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 7;
    e = load_error("d.gltf", bad_view.gltf());
    EXPECT_TRUE(has(e, at + ".bufferView: bufferView 7 does not exist")) << e;
    TestFile bad_count = good;
    bad_count.doc["accessors"][1]["count"] = 5;
    e = load_error("d.gltf", bad_count.gltf());
    EXPECT_TRUE(has(e, "d.gltf: accessors[1].count: 5 differs from the 36 points of the Draco data")) << e;
    TestFile missing = good;
    missing.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"].erase("attributes");
    e = load_error("d.gltf", missing.gltf());
    EXPECT_TRUE(has(e, at + ".attributes: required")) << e;
    // Over the triangle limit: refused before anything is converted.
    e = load_error("d.gltf", good.gltf(), 10);
    EXPECT_TRUE(has(e, "exceed the limit of 10 triangles")) << e;
    // Control: the untouched file loads.
    EXPECT_EQ(only_primitive(load("d.gltf", good.gltf())).vertices.size(), mesh.idx.size());
}

// Every byte of good's binary chunk flipped in three ways (low bit, high bit,
// all bits), one at a time: each file loads or is refused with a message
// naming it, and at least one is refused.
static void expect_corruptions_load_or_are_refused(const TestFile& good, const std::string& name) {
    int refused = 0, loaded = 0;
    for (std::size_t i = 0; i < good.bin.size(); ++i)
        for (unsigned char x : {0x01, 0x80, 0xff}) {
            TestFile f = good;
            f.bin[i] = char(f.bin[i] ^ x);
            try {
                (void)load(name, f.glb());
                ++loaded;
            } catch (const Error& e) {
                ++refused;
                EXPECT_TRUE(has(e.what(), name + ": ")) << e.what();
            }
        }
    EXPECT_GT(refused, 0);
    EXPECT_EQ(refused + loaded, int(3 * good.bin.size()));
}

// Every single-byte corruption of the Draco data either decodes to something
// the loader checks like any accessor, or is refused: never a crash.
TEST(GltfCompressed, CorruptDracoBytesNeverCrash) {
    expect_corruptions_load_or_are_refused(draco_file(bumpy_grid(5, false)), "d.glb");
}

TEST(GltfCompressed, BadMeshoptViewsAreErrorsNamingTheField) {
    const TestMesh mesh = bumpy_grid(6, false);
    const TestFile good = meshopt_file(mesh);
    const std::string at = "m.gltf: bufferViews[0].extensions.EXT_meshopt_compression";
    auto error = [&](auto change) {
        TestFile f = good;
        change(f.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"], f);
        return load_error("m.gltf", f.gltf());
    };
    std::string e = error([](json& x, TestFile&) { x["byteLength"] = 1u << 20; });
    EXPECT_TRUE(has(e, at + ": bytes ") && has(e, "run past the end of buffers[0]")) << e;
    e = error([](json& x, TestFile&) { x["byteOffset"] = 1e15; });
    EXPECT_TRUE(has(e, at + ": bytes ") && has(e, "run past the end of buffers[0]")) << e;
    e = error([](json& x, TestFile&) { x["count"] = 37; });
    EXPECT_TRUE(has(e, at + ": count 37 times byteStride 12 is 444 bytes, but the bufferView's byteLength is 432")) << e;
    e = error([](json& x, TestFile&) { x["count"] = 1e12; });
    EXPECT_TRUE(has(e, at + ".count: 1000000000000 exceeds the limit of")) << e;
    e = error([](json& x, TestFile&) { x["byteStride"] = 6; });
    EXPECT_TRUE(has(e, at + ".byteStride: 6 differs from the bufferView's byteStride 12")) << e;
    e = error([](json& x, TestFile& f) {
        x["byteStride"] = 6;
        f.doc["bufferViews"][0].erase("byteStride");
    });
    EXPECT_TRUE(has(e, at + ".byteStride: 6 must be a multiple of 4 for mode ATTRIBUTES")) << e;
    e = error([](json& x, TestFile&) { x["byteStride"] = 300; });
    EXPECT_TRUE(has(e, at + ".byteStride: 300 is out of range (must be from 1 to 256)")) << e;
    e = error([](json& x, TestFile&) { x["mode"] = "QUADS"; });
    EXPECT_TRUE(has(e, at + ".mode: 'QUADS' is not one of ATTRIBUTES, TRIANGLES, INDICES")) << e;
    e = error([](json& x, TestFile&) { x["filter"] = "WAVELET"; });
    EXPECT_TRUE(has(e, at + ".filter: 'WAVELET' is not one of NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL")) << e;
    e = error([](json& x, TestFile&) { x["filter"] = "QUATERNION"; });
    EXPECT_TRUE(has(e, at + ".byteStride: 12 must be 8 for filter QUATERNION")) << e;
    e = error([](json& x, TestFile&) { x["buffer"] = 5; });
    EXPECT_TRUE(has(e, at + ".buffer: buffer 5 does not exist (the file has 2)")) << e;
    e = error([](json& x, TestFile&) { x["buffer"] = 1; });
    EXPECT_TRUE(has(e, at + ".buffer: buffers[1] is a fallback buffer")) << e;
    e = error([](json& x, TestFile&) { x.erase("count"); });
    EXPECT_TRUE(has(e, at + ".count: required, but missing")) << e;
    e = error([](json& x, TestFile&) { x["byteLength"] = x["byteLength"].get<std::size_t>() - 8; });  // truncated
    EXPECT_TRUE(has(e, at + ": the ") && has(e, "corrupt or truncated data")) << e;
    // The index view: TRIANGLES needs whole triangles and 2- or 4-byte indices.
    const std::string iat = "m.gltf: bufferViews[3].extensions.EXT_meshopt_compression";
    TestFile f = good;
    f.doc["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 8;
    f.doc["bufferViews"][3]["byteLength"] = f.doc["bufferViews"][3]["byteLength"].get<std::size_t>() * 2;
    e = load_error("m.gltf", f.gltf());
    EXPECT_TRUE(has(e, iat + ".byteStride: 8 must be 2 or 4 for mode TRIANGLES")) << e;
    // A view without the extension may not read the fallback buffer.
    f = good;
    f.doc["bufferViews"][0].erase("extensions");
    e = load_error("m.gltf", f.gltf());
    EXPECT_TRUE(has(e, "m.gltf: bufferViews[0]: buffers[1] is an EXT_meshopt_compression fallback buffer")) << e;
    // An accessor's view out of range is named as before.
    f = good;
    f.doc["accessors"][0]["bufferView"] = 40;
    e = load_error("m.gltf", f.gltf());
    EXPECT_TRUE(has(e, "m.gltf: accessors[0].bufferView: bufferView 40 does not exist")) << e;
    // Control.
    EXPECT_EQ(only_primitive(load("m.gltf", good.gltf())).vertices.size(), mesh.idx.size());
}

TEST(GltfCompressed, CorruptMeshoptBytesNeverCrash) {
    expect_corruptions_load_or_are_refused(meshopt_file(bumpy_grid(5, false)), "m.glb");
}
