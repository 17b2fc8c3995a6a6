// EXT_meshopt_compression: buffer views stored compressed by meshoptimizer's
// codecs (the extension's README, "JSON schema updates" and "Appendix A"),
// decoded through Debian's libmeshoptimizer. meshoptimizer asserts its
// preconditions rather than reporting them, so every rule the specification
// lists is checked here first, with the field at fault named.
#include <set>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "scene/load/gltf_parts.hpp"

namespace clpath::gltf {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

std::string list_of(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::string one_of(const Source& src, const tinygltf::Value& o, const char* key, const std::string& path,
                   const std::vector<std::string>& allowed, std::optional<std::string> absent = std::nullopt) {
    const std::string v = string_field(src, o, key, path, absent);
    for (const auto& a : allowed)
        if (v == a) return v;
    std::string what = "'";
    what += v.substr(0, 40);
    src.fail(path + "." + key, what + "' is not one of " + list_of(allowed));
}

}  // namespace

bool is_fallback_buffer(const tinygltf::Buffer& buffer) {
    const auto it = buffer.extensions.find(kExtension);
    if (it == buffer.extensions.end() || !it->second.IsObject() || !it->second.Has("fallback")) return false;
    const tinygltf::Value& f = it->second.Get("fallback");
    return f.IsBool() && f.Get<bool>();
}

const std::vector<unsigned char>* meshopt_view(const Source& src, int index) {
    const auto& m = src.model;
    const tinygltf::BufferView& bv = m.bufferViews[std::size_t(index)];
    const auto ext = bv.extensions.find(kExtension);
    if (ext == bv.extensions.end()) return nullptr;
    if (auto done = src.meshopt_views.find(index); done != src.meshopt_views.end()) return &done->second;

    const std::string path = "bufferViews[" + std::to_string(index) + "].extensions." + kExtension;
    const tinygltf::Value& e = ext->second;
    if (!e.IsObject()) src.fail(path, "expected an object");
    const std::int64_t buffer = whole_field(src, e, "buffer", path, 0, INT32_MAX);
    if (std::size_t(buffer) >= m.buffers.size())
        src.fail(path + ".buffer", "buffer " + std::to_string(buffer) + " does not exist (the file has " +
                                       std::to_string(m.buffers.size()) + ")");
    if (is_fallback_buffer(m.buffers[std::size_t(buffer)]))
        src.fail(path + ".buffer", "buffers[" + std::to_string(buffer) +
                                       "] is a fallback buffer, which holds no compressed data");
    const std::int64_t offset = whole_field(src, e, "byteOffset", path, 0, INT64_MAX, 0);
    const std::int64_t length = whole_field(src, e, "byteLength", path, 1, INT64_MAX);
    const std::int64_t stride = whole_field(src, e, "byteStride", path, 1, 256);
    const std::int64_t count = whole_field(src, e, "count", path, 1, INT64_MAX);
    const std::string mode = one_of(src, e, "mode", path, {"ATTRIBUTES", "TRIANGLES", "INDICES"});
    const std::string filter =
        one_of(src, e, "filter", path, {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"}, std::string("NONE"));

    // The specification's rules, in its order.
    const std::string s = std::to_string(stride);
    if (bv.byteStride && std::int64_t(bv.byteStride) != stride)
        src.fail(path + ".byteStride", s + " differs from the bufferView's byteStride " + std::to_string(bv.byteStride));
    if (mode == "ATTRIBUTES" && stride % 4)
        src.fail(path + ".byteStride", s + " must be a multiple of 4 for mode ATTRIBUTES");
    if (mode == "TRIANGLES" && count % 3)
        src.fail(path + ".count", std::to_string(count) + " must be a multiple of 3 for mode TRIANGLES");
    if (mode != "ATTRIBUTES" && stride != 2 && stride != 4)
        src.fail(path + ".byteStride", s + " must be 2 or 4 for mode " + mode);
    if (mode != "ATTRIBUTES" && filter != "NONE")
        src.fail(path + ".filter", filter + " is not allowed for mode " + mode + " (only NONE)");
    if (filter == "OCTAHEDRAL" && stride != 4 && stride != 8)
        src.fail(path + ".byteStride", s + " must be 4 or 8 for filter OCTAHEDRAL");
    if (filter == "QUATERNION" && stride != 8) src.fail(path + ".byteStride", s + " must be 8 for filter QUATERNION");
    if (filter == "EXPONENTIAL" && stride % 4)
        src.fail(path + ".byteStride", s + " must be a multiple of 4 for filter EXPONENTIAL");
    // Decoded sizes are capped as accessors' counts are, before anything is allocated.
    const std::int64_t max_count = std::int64_t(3) * std::int64_t(src.options.max_triangles) + 2;
    if (count > max_count)
        src.fail(path + ".count", std::to_string(count) + " exceeds the limit of " + std::to_string(max_count));
    const std::size_t decoded = std::size_t(count) * std::size_t(stride);  // at most 256 * max_count
    if (decoded != bv.byteLength)
        src.fail(path, "count " + std::to_string(count) + " times byteStride " + s + " is " + std::to_string(decoded) +
                           " bytes, but the bufferView's byteLength is " + std::to_string(bv.byteLength));
    const auto& data = m.buffers[std::size_t(buffer)].data;
    if (std::uint64_t(offset) > data.size() || std::uint64_t(length) > data.size() - std::size_t(offset))
        src.fail(path, "bytes " + std::to_string(offset) + " + " + std::to_string(length) + " run past the end of buffers[" +
                           std::to_string(buffer) + "] (" + std::to_string(data.size()) + " bytes)");

    std::vector<unsigned char> out(decoded);
    const unsigned char* in = data.data() + offset;
    const std::size_t n = std::size_t(count), size = std::size_t(stride), in_size = std::size_t(length);
    int rc = 0;
    const char* codec = "";
    if (mode == "ATTRIBUTES") {
        codec = "meshopt_decodeVertexBuffer";
        rc = meshopt_decodeVertexBuffer(out.data(), n, size, in, in_size);
    } else if (mode == "TRIANGLES") {
        codec = "meshopt_decodeIndexBuffer";
        rc = meshopt_decodeIndexBuffer(out.data(), n, size, in, in_size);
    } else {
        codec = "meshopt_decodeIndexSequence";
        rc = meshopt_decodeIndexSequence(out.data(), n, size, in, in_size);
    }
    if (rc != 0)
        src.fail(path, "the " + std::to_string(length) + " compressed bytes do not decode to " + std::to_string(count) +
                           " elements of " + s + " bytes in mode " + mode + " (" + codec + " returned " +
                           std::to_string(rc) + ": corrupt or truncated data)");
    // The filters turn the decoded integers back into what the accessors read (Appendix B).
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), n, size);
    else if (filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), n, size);
    else if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), n, size);
    return &(src.meshopt_views[index] = std::move(out));
}

bool stand_in_fallback_buffers(nlohmann::json& doc, bool binary, DataUris& uris) {
    auto buffers = doc.find("buffers");
    if (buffers == doc.end() || !buffers->is_array()) return false;
    // The buffers some uncompressed view reads, and those compressed views name as their fallback.
    std::set<std::size_t> read, behind_compressed;
    if (auto views = doc.find("bufferViews"); views != doc.end() && views->is_array())
        for (const auto& v : *views) {
            if (!v.is_object() || !v.contains("buffer") || !v["buffer"].is_number_unsigned()) continue;
            const std::size_t b = v["buffer"].get<std::size_t>();
            const auto ext = v.find("extensions");
            const bool compressed = ext != v.end() && ext->is_object() && ext->contains(kExtension);
            (compressed ? behind_compressed : read).insert(b);
        }
    bool changed = false;
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& b = (*buffers)[i];
        if (!b.is_object() || b.contains("uri") || (binary && i == 0)) continue;  // a GLB's buffer 0 is its BIN chunk
        const auto ext = b.find("extensions");
        if (ext != b.end() && !ext->is_object()) continue;  // not a place to mark: left to tinygltf
        const nlohmann::json* mark = ext != b.end() && ext->contains(kExtension) ? &(*ext)[kExtension] : nullptr;
        const bool marked = mark && mark->is_object() && mark->contains("fallback") && (*mark)["fallback"] == true;
        if (!marked && (read.count(i) || !behind_compressed.count(i))) continue;  // left to tinygltf, which refuses it
        const std::string name = kDataUriPrefix + std::to_string(uris.size() + 1) + ")";
        uris.emplace_back(name, std::vector<unsigned char>(1, 0));
        b["uri"] = name;
        b["byteLength"] = 1;
        b["extensions"][kExtension] = {{"fallback", true}};
        changed = true;
    }
    return changed;
}

}  // namespace clpath::gltf
