#pragma once
// Small glTF files written by the tests: a buffer assembled from typed
// arrays, embedded as a base64 data URI (or kept as an external .bin), and
// the JSON around it built with nlohmann::json.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "memory_files.hpp"
#include "scene/load/gltf_scene.hpp"

namespace clpath::test {

inline std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
    }
    if (i + 1 == in.size()) {
        const unsigned v = (unsigned char)in[i] << 16;
        out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == in.size()) {
        const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
    }
    return out;
}

// A glTF document under construction: arrays appended to one buffer, each
// with its own buffer view and accessor.
struct GltfBuilder {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}, {"buffers", nlohmann::json::array()},
                          {"bufferViews", nlohmann::json::array()}, {"accessors", nlohmann::json::array()}};
    std::string bin;

    template <class T>
    int accessor(const std::vector<T>& values, int component_type, const std::string& type, std::size_t count) {
        while (bin.size() % 4) bin += '\0';
        const std::size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                    {"componentType", component_type},
                                    {"count", count},
                                    {"type", type}});
        return int(doc["accessors"].size() - 1);
    }
    int floats(const std::vector<float>& v, const std::string& type, int per) {
        return accessor(v, 5126, type, v.size() / std::size_t(per));
    }
    int indices(const std::vector<std::uint16_t>& v) { return accessor(v, 5123, "SCALAR", v.size()); }

    // The document with the buffer embedded as a data URI.
    std::string embedded() const {
        nlohmann::json d = doc;
        d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
        return d.dump();
    }
    // The document naming an external buffer file.
    std::string external(const std::string& bin_name) const {
        nlohmann::json d = doc;
        d["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_name}}};
        return d.dump();
    }
    // A binary .glb: header, JSON chunk, BIN chunk.
    std::string glb() const {
        nlohmann::json d = doc;
        d["buffers"] = {{{"byteLength", bin.size()}}};
        std::string json = d.dump();
        while (json.size() % 4) json += ' ';
        std::string b = bin;
        while (b.size() % 4) b += '\0';
        auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
        return "glTF" + u32(2) + u32(std::uint32_t(12 + 8 + json.size() + 8 + b.size())) + u32(std::uint32_t(json.size())) +
               "JSON" + json + u32(std::uint32_t(b.size())) + std::string("BIN\0", 4) + b;
    }
};

// One unit quad in the z = 0 plane facing +z (two triangles), indexed, with
// normals and texture coordinates, in mesh 0 placed by node 0.
inline GltfBuilder quad_model() {
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    const int nrm = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int uv = g.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
    const int idx = g.indices({0, 1, 2, 0, 2, 3});
    nlohmann::json prim = {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", idx}};
    g.doc["meshes"] = nlohmann::json::array({nlohmann::json{{"primitives", nlohmann::json::array({prim})}}});
    g.doc["nodes"] = nlohmann::json::array({nlohmann::json{{"mesh", 0}}});
    g.doc["scenes"] = nlohmann::json::array({nlohmann::json{{"nodes", nlohmann::json::array({0})}}});
    g.doc["scene"] = 0;
    return g;
}

// A glTF file given as text, loaded as `clpath render` loads it but without
// the presentation's ground: the scene holds the file's own triangles only.
inline Scene gltf_text_scene(const std::string& name, const std::string& text) {
    MemoryFiles f;
    f.files[name] = text;
    LoadOptions o = f.options();
    o.presentation.ground = false;
    return gltf_scene(name, o);
}

// The message loading that text fails with.
inline std::string gltf_text_error(const std::string& name, const std::string& text) {
    return error_of([&] { (void)gltf_text_scene(name, text); });
}

// A texture decoder that needs no image library: "RGBA", then width and
// height as one byte each, then the texels.
inline TextureImage fake_rgba_decode(const std::string& bytes, const std::string& name) {
    if (bytes.size() < 6 || bytes.compare(0, 4, "RGBA") != 0) throw Error(name + ": cannot decode the image: not RGBA");
    TextureImage t;
    t.width = (unsigned char)bytes[4];
    t.height = (unsigned char)bytes[5];
    t.rgba8.assign(bytes.begin() + 6, bytes.end());
    if (t.rgba8.size() != std::size_t(t.width) * t.height * 4) throw Error(name + ": cannot decode the image: short");
    return t;
}

}  // namespace clpath::test
