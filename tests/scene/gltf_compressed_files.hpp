#pragma once
// Compressed glTF files made by the tests from an uncompressed original with
// the libraries' own encoders (draco::Encoder, meshopt_encode*), so nothing
// compressed is committed or downloaded, and each can be compared with the
// file it came from.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "gltf_files.hpp"

namespace clpath::test {

// An indexed triangle mesh: 3 floats per position and normal, 2 per texture coordinate.
struct TestMesh {
    std::vector<float> pos, nrm, uv;
    std::vector<std::uint32_t> idx;
    std::size_t vertices() const { return pos.size() / 3; }
};

// n x n vertices over a bumpy sheet, with its analytic unit normals and a
// [0,1]^2 parametrisation. With `on_grid` the positions are whole numbers
// from 0 to 2047 in x and y (a range of exactly 2^11 - 1), so that Draco's
// 11-bit quantisation, whose step is range / (2^11 - 1) = 1, keeps them exactly.
inline TestMesh bumpy_grid(int n, bool on_grid) {
    TestMesh m;
    const float scale = on_grid ? 2047.0f : 1.0f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float u = float(i) / float(n - 1), v = float(j) / float(n - 1);
            // z = a sin(2 pi u) cos(pi v) over [0, s]^2; normal (-dz/dx, -dz/dy, 1), normalised.
            const float a = 0.15f, kx = 2 * float(M_PI), ky = float(M_PI);
            float x = u * scale, y = v * scale, z = a * scale * std::sin(kx * u) * std::cos(ky * v);
            if (on_grid) x = std::round(x), y = std::round(y), z = std::round(z);
            const float dzdx = a * kx * std::cos(kx * u) * std::cos(ky * v), dzdy = -a * ky * std::sin(kx * u) * std::sin(ky * v);
            const float len = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1);
            m.pos.insert(m.pos.end(), {x, y, z});
            m.nrm.insert(m.nrm.end(), {-dzdx / len, -dzdy / len, 1 / len});
            m.uv.insert(m.uv.end(), {u, v});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const std::uint32_t a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
            m.idx.insert(m.idx.end(), {a, b, d, a, d, c});
        }
    return m;
}

// A document and its one binary buffer (buffers[0]), written as a .gltf
// with the buffer as a data URI or as a .glb with it as the BIN chunk.
struct TestFile {
    nlohmann::json doc;
    std::string bin;

    std::string gltf() const {
        nlohmann::json d = doc;
        d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
        return d.dump();
    }
    std::string glb() const {
        std::string json = doc.dump();
        while (json.size() % 4) json += ' ';
        std::string b = bin;
        while (b.size() % 4) b += '\0';
        auto u32 = [](std::size_t v) {
            const std::uint32_t x = std::uint32_t(v);
            return std::string(reinterpret_cast<const char*>(&x), 4);
        };
        return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + b.size()) + u32(json.size()) + "JSON" + json +
               u32(b.size()) + std::string("BIN\0", 4) + b;
    }
    // Appends bytes to the binary buffer (4-byte aligned); returns their offset.
    std::size_t append(const void* data, std::size_t size) {
        while (bin.size() % 4) bin += '\0';
        const std::size_t at = bin.size();
        bin.append(static_cast<const char*>(data), size);
        return at;
    }
    int accessor(int view, int component_type, const std::string& type, std::size_t count, bool normalized = false) {
        nlohmann::json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
        if (view >= 0) a["bufferView"] = view;
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size() - 1);
    }
    // Mesh 0 with one primitive, placed by node 0 of scene 0.
    void place(const nlohmann::json& primitive) {
        doc["meshes"] = nlohmann::json::array({nlohmann::json{{"primitives", nlohmann::json::array({primitive})}}});
        doc["nodes"] = nlohmann::json::array({nlohmann::json{{"mesh", 0}}});
        doc["scenes"] = nlohmann::json::array({nlohmann::json{{"nodes", nlohmann::json::array({0})}}});
        doc["scene"] = 0;
    }
    void require(const std::string& extension) {
        doc["extensionsUsed"].push_back(extension);
        doc["extensionsRequired"].push_back(extension);
    }
};

inline TestFile empty_file() {
    TestFile f;
    f.doc = {{"asset", {{"version", "2.0"}}}, {"buffers", nlohmann::json::array({nlohmann::json{{"byteLength", 0}}})},
             {"bufferViews", nlohmann::json::array()}, {"accessors", nlohmann::json::array()}};
    return f;
}

constexpr int kGltfFloat = 5126, kGltfUInt = 5125, kGltfShort = 5122;

// The original: float attributes and 32-bit indices, uncompressed.
inline TestFile plain_file(const TestMesh& m, bool with_uv = true) {
    TestFile f = empty_file();
    auto view = [&](const void* data, std::size_t size) {
        const std::size_t at = f.append(data, size);
        f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", size}});
        return int(f.doc["bufferViews"].size() - 1);
    };
    const std::size_t n = m.vertices();
    nlohmann::json attrs = {
        {"POSITION", f.accessor(view(m.pos.data(), m.pos.size() * 4), kGltfFloat, "VEC3", n)},
        {"NORMAL", f.accessor(view(m.nrm.data(), m.nrm.size() * 4), kGltfFloat, "VEC3", n)}};
    if (with_uv) attrs["TEXCOORD_0"] = f.accessor(view(m.uv.data(), m.uv.size() * 4), kGltfFloat, "VEC2", n);
    const int idx = f.accessor(view(m.idx.data(), m.idx.size() * 4), kGltfUInt, "SCALAR", m.idx.size());
    f.doc["buffers"][0]["byteLength"] = f.bin.size();
    f.place({{"attributes", attrs}, {"indices", idx}});
    return f;
}

struct MeshoptChoice {
    std::string index_mode = "TRIANGLES";  // or INDICES
    bool octahedral_normals = false;       // normals as 16-bit snorm, filter OCTAHEDRAL (lossy); else floats, lossless
    bool mark_fallback = true;             // the fallback buffer carries "fallback": true
};

// The original with every buffer view compressed by EXT_meshopt_compression;
// the uncompressed views sit in a fallback buffer (buffers[1]) without data.
inline TestFile meshopt_file(const TestMesh& m, const MeshoptChoice& c = {}, bool with_uv = true) {
    TestFile f = empty_file();
    f.require("EXT_meshopt_compression");
    std::size_t fallback_size = 0;
    // A view of `count` elements of `stride` bytes whose encoding is `encoded`.
    auto view = [&](const std::vector<unsigned char>& encoded, std::size_t count, std::size_t stride, const std::string& mode,
                    const std::string& filter, bool attribute) {
        const std::size_t at = f.append(encoded.data(), encoded.size());
        nlohmann::json ext = {{"buffer", 0}, {"byteOffset", at}, {"byteLength", encoded.size()}, {"byteStride", stride},
                              {"count", count}, {"mode", mode}};
        if (filter != "NONE") ext["filter"] = filter;
        nlohmann::json v = {{"buffer", 1}, {"byteOffset", fallback_size}, {"byteLength", count * stride},
                            {"extensions", {{"EXT_meshopt_compression", ext}}}};
        if (attribute) v["byteStride"] = stride;
        fallback_size += (count * stride + 3) / 4 * 4;
        f.doc["bufferViews"].push_back(v);
        return int(f.doc["bufferViews"].size() - 1);
    };
    auto vertices = [&](const void* data, std::size_t stride, const std::string& filter = "NONE") {
        std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(m.vertices(), stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, m.vertices(), stride));
        return view(out, m.vertices(), stride, "ATTRIBUTES", filter, true);
    };
    const std::size_t n = m.vertices();
    nlohmann::json attrs = {{"POSITION", f.accessor(vertices(m.pos.data(), 12), kGltfFloat, "VEC3", n)}};
    if (c.octahedral_normals) {
        std::vector<float> n4;
        for (std::size_t i = 0; i < n; ++i) n4.insert(n4.end(), {m.nrm[3 * i], m.nrm[3 * i + 1], m.nrm[3 * i + 2], 0.0f});
        std::vector<std::int16_t> oct(4 * n);
        meshopt_encodeFilterOct(oct.data(), n, 8, 16, n4.data());
        attrs["NORMAL"] = f.accessor(vertices(oct.data(), 8, "OCTAHEDRAL"), kGltfShort, "VEC3", n, true);
    } else {
        attrs["NORMAL"] = f.accessor(vertices(m.nrm.data(), 12), kGltfFloat, "VEC3", n);
    }
    if (with_uv) attrs["TEXCOORD_0"] = f.accessor(vertices(m.uv.data(), 8), kGltfFloat, "VEC2", n);
    std::vector<unsigned char> ie;
    if (c.index_mode == "TRIANGLES") {
        ie.resize(meshopt_encodeIndexBufferBound(m.idx.size(), n));
        ie.resize(meshopt_encodeIndexBuffer(ie.data(), ie.size(), m.idx.data(), m.idx.size()));
    } else {
        ie.resize(meshopt_encodeIndexSequenceBound(m.idx.size(), n));
        ie.resize(meshopt_encodeIndexSequence(ie.data(), ie.size(), m.idx.data(), m.idx.size()));
    }
    const int idx = f.accessor(view(ie, m.idx.size(), 4, c.index_mode, "NONE", false), kGltfUInt, "SCALAR", m.idx.size());
    f.doc["buffers"][0]["byteLength"] = f.bin.size();
    nlohmann::json fallback = {{"byteLength", fallback_size}};
    if (c.mark_fallback) fallback["extensions"] = {{"EXT_meshopt_compression", {{"fallback", true}}}};
    f.doc["buffers"].push_back(fallback);
    f.place({{"attributes", attrs}, {"indices", idx}});
    return f;
}

struct DracoChoice {
    int position_bits = 14;  // 0: unquantised
    int uv_bits = 12;
    bool sequential = true;  // MESH_SEQUENTIAL_ENCODING keeps point and face order; else edgebreaker
};

// The mesh as Draco encodes it with draco::Encoder.
inline std::string draco_bytes(const TestMesh& m, const DracoChoice& c, bool with_uv, int ids[3]) {
    draco::Mesh mesh;
    const std::size_t n = m.vertices();
    mesh.set_num_points(std::uint32_t(n));
    auto add = [&](draco::GeometryAttribute::Type type, const std::vector<float>& values, int components) {
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, std::int8_t(components), draco::DT_FLOAT32, false, 4 * components, 0);
        const int id = mesh.AddAttribute(ga, true, std::uint32_t(n));
        for (std::size_t i = 0; i < n; ++i)
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(std::uint32_t(i)), &values[i * std::size_t(components)]);
        return int(mesh.attribute(id)->unique_id());
    };
    ids[0] = add(draco::GeometryAttribute::POSITION, m.pos, 3);
    ids[1] = add(draco::GeometryAttribute::NORMAL, m.nrm, 3);
    if (with_uv) ids[2] = add(draco::GeometryAttribute::TEX_COORD, m.uv, 2);
    for (std::size_t t = 0; t < m.idx.size(); t += 3)
        mesh.AddFace({draco::PointIndex(m.idx[t]), draco::PointIndex(m.idx[t + 1]), draco::PointIndex(m.idx[t + 2])});
    draco::Encoder enc;
    if (c.position_bits) enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, c.position_bits);
    if (c.uv_bits) enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, c.uv_bits);
    enc.SetEncodingMethod(c.sequential ? draco::MESH_SEQUENTIAL_ENCODING : draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer out;
    const draco::Status s = enc.EncodeMeshToBuffer(mesh, &out);
    if (!s.ok()) ADD_FAILURE() << "draco encoder: " << s.error_msg_string();
    return std::string(out.data(), out.size());
}

// The original as a KHR_draco_mesh_compression primitive: its accessors
// without buffer views, its data in bufferViews[0].
inline TestFile draco_file(const TestMesh& m, const DracoChoice& c = {}, bool with_uv = true) {
    TestFile f = empty_file();
    f.require("KHR_draco_mesh_compression");
    int ids[3] = {0, 0, 0};
    const std::string bytes = draco_bytes(m, c, with_uv, ids);
    const std::size_t at = f.append(bytes.data(), bytes.size());
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", bytes.size()}});
    f.doc["buffers"][0]["byteLength"] = f.bin.size();
    const std::size_t n = m.vertices();
    nlohmann::json attrs = {{"POSITION", f.accessor(-1, kGltfFloat, "VEC3", n)}, {"NORMAL", f.accessor(-1, kGltfFloat, "VEC3", n)}};
    nlohmann::json ids_json = {{"POSITION", ids[0]}, {"NORMAL", ids[1]}};
    if (with_uv) {
        attrs["TEXCOORD_0"] = f.accessor(-1, kGltfFloat, "VEC2", n);
        ids_json["TEXCOORD_0"] = ids[2];
    }
    const int idx = f.accessor(-1, kGltfUInt, "SCALAR", m.idx.size());
    f.place({{"attributes", attrs},
             {"indices", idx},
             {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", ids_json}}}}}});
    return f;
}

}  // namespace clpath::test
