// libFuzzer target: the glTF loader against hostile document structure. Each
// input is read as a recipe for a well-formed glTF document (so no run is
// spent on JSON syntax): how many nodes, which children each lists (the same
// child twice, a shared child, itself, an ancestor: cycles), which place the
// quad mesh, a camera or a light, how deep node 0's "extras" nest (past the
// loader's limit too), which scenes there are and which is the default, and
// whether it comes as .gltf or .glb. Any recipe must end in a Scene or a
// clpath::Error, quickly: the deterministic CTest run has a 10 s timeout.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_files.hpp"
#include "scene/load/gltf_scene.hpp"

namespace {

struct Recipe {
    const std::uint8_t* data;
    std::size_t size, at = 0;
    unsigned byte() { return at < size ? data[at++] : 0u; }
};

std::string nested(unsigned depth, unsigned pattern) {
    std::string open, close;
    for (unsigned i = 0; i < depth; ++i) {
        const bool array = (pattern >> (i % 8)) & 1;
        open += array ? "[" : "{\"x\":";
        close += array ? "]" : "}";
    }
    return open + "1" + std::string(close.rbegin(), close.rend());
}

std::string glb(const std::string& json_text) {
    std::string j = json_text;
    while (j.size() % 4) j += ' ';
    auto u32 = [](std::size_t v) {
        const auto x = std::uint32_t(v);
        return std::string(reinterpret_cast<const char*>(&x), 4);
    };
    return "glTF" + u32(2) + u32(20 + j.size()) + u32(j.size()) + "JSON" + j;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using nlohmann::json;
    Recipe r{data, size};
    const unsigned n = 1 + r.byte() % 48;
    json doc = json::parse(R"({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 60, "uri": "model.bin"}],
        "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
                    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 10}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5}]}}})");
    json nodes = json::array();
    for (unsigned i = 0; i < n; ++i) {
        json node = json::object();
        const unsigned children = r.byte() % 4;
        for (unsigned c = 0; c < children; ++c) node["children"].push_back(r.byte() % n);
        const unsigned flags = r.byte();
        if (flags & 1) node["mesh"] = 0;
        if (flags & 2) node["camera"] = (flags >> 3) & 1;
        if (flags & 4) node["extensions"]["KHR_lights_punctual"]["light"] = 0;
        if (flags & 16) node["translation"] = {double(flags >> 5), 0, -1};
        nodes.push_back(node);
    }
    doc["nodes"] = nodes;
    switch (r.byte() % 4) {
    case 0: break;  // no scenes: every node that is no other's child is a root
    case 1: {
        json roots = json::array();
        for (unsigned i = 0, k = 1 + r.byte() % 4; i < k; ++i) roots.push_back(r.byte() % n);
        doc["scenes"] = {{{"nodes", roots}}};
        break;
    }
    case 2:
        doc["scenes"] = json::array();
        doc["scene"] = 0;
        break;
    default:
        doc["scenes"] = {{{"nodes", {0}}}, {{"nodes", {n - 1}}}};
        doc["scene"] = r.byte() % 3;
    }
    const unsigned depth = (r.byte() << 8 | r.byte()) % 1200;
    std::string text = doc.dump();
    if (depth) text = text.substr(0, text.size() - 1) + ",\"extras\":" + nested(depth, r.byte()) + "}";
    const bool binary = r.byte() & 1;
    const std::string name = binary ? "fuzz/model.glb" : "fuzz/model.gltf";
    const std::string input = binary ? glb(text) : text;

    clpath::LoadOptions o = clpath::fuzz::options();
    // A low limit on placed nodes: recipes reach it often (so the refusal is
    // explored as much as the walk), and each accepted one builds in
    // milliseconds, which keeps the CTest run's fixed 20,000 inputs short.
    o.max_placed_nodes = 256;
    const auto files = o.read_file;
    o.read_file = [&](const std::string& path) { return path == name ? input : files(path); };
    const auto exists = o.file_exists;
    o.file_exists = [&](const std::string& path) { return path == name || exists(path); };
    try {
        clpath::fuzz::check_scene(clpath::gltf_scene(name, o));
    } catch (const clpath::Error&) {
    }
    return 0;
}
