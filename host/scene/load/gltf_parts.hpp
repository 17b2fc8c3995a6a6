#pragma once
// The parts of the glTF loader (gltf_model.hpp), shared between its files:
// checked accessor reads and the material and texture conversion.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include "scene/load/gltf_model.hpp"

namespace clpath::gltf {

// The glTF document and where messages point.
struct Source {
    const tinygltf::Model& model;
    std::string file;
    const LoadOptions& options;
    // Throws clpath::Error "FILE: PATH: what".
    [[noreturn]] void fail(const std::string& path, const std::string& what) const;
    // EXT_meshopt_compression buffer views, decoded when an accessor first
    // reads them (meshopt_view), by bufferView index.
    mutable std::map<int, std::vector<unsigned char>> meshopt_views{};
};

// Bytes per component of a TINYGLTF_COMPONENT_TYPE_*, components per
// TINYGLTF_TYPE_* (0 for others).
int component_size(int component_type);
int type_components(int type);

// o[key] of an extension object (tinygltf keeps extensions as generic
// values): a whole number in [lo, hi], else src.fail naming path.key; when
// absent, `absent` if given, else "required, but missing".
std::int64_t whole_field(const Source& src, const tinygltf::Value& o, const char* key, const std::string& path,
                         std::int64_t lo, std::int64_t hi, std::optional<std::int64_t> absent = std::nullopt);
// o[key]: a string, required unless `absent` is given (returned when absent).
std::string string_field(const Source& src, const tinygltf::Value& o, const char* key, const std::string& path,
                         std::optional<std::string> absent = std::nullopt);

// The bytes of bufferViews[index], bounds-checked against its buffer, or
// decoded when the view is EXT_meshopt_compression-compressed; `referrer`
// is the glTF path that names the view, for messages.
struct Bytes {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};
Bytes buffer_view_bytes(const Source& src, int index, const std::string& referrer);

// An accessor's elements, bounds-checked against its buffer view and buffer.
// data is null for an accessor without a buffer view (all zeros, as the
// specification says).
struct View {
    const unsigned char* data = nullptr;
    std::size_t count = 0, stride = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
    std::string path;  // the accessor's glTF path, for messages
    // Every element as `width` floats (width >= components; the components
    // past the accessor's get `fill`), count * width in all; normalized
    // integers mapped to [0,1] or [-1,1] (KHR glTF 2.0 section 3.11, signed
    // ones clamp at -1). One switch per accessor, not per component: a
    // million-triangle mesh has millions of components.
    std::vector<float> floats(int width, float fill = 0) const;
    // Every element of an index accessor.
    std::vector<std::uint32_t> indices() const;
};

// The accessor `index`, named `path` in messages, which must be of type
// `type` (TINYGLTF_TYPE_*, or any of two when alt_type >= 0) and of a
// component type in `allowed` (float ones are converted, integer ones only
// when normalized unless `integers` says they are indices, or
// `plain_integers` that unnormalized ones are values, as
// KHR_mesh_quantization allows for positions and texture coordinates).
View view(const Source& src, int index, const std::string& path, int type, int alt_type,
          const std::vector<int>& allowed, bool integers = false, bool plain_integers = false);

// Base64 data URIs of buffers in a .gltf's text, decoded here rather than
// by tinygltf: its decoder and two JSON parses (check_uris and tinygltf's) of
// a text holding tens of megabytes of base64 took seconds for a
// million-triangle mesh. Each is replaced by a name that the loader's file
// callbacks serve (find_data_uri); image URIs and anything that is not plain
// base64 are left as they are.
using DataUris = std::vector<std::pair<std::string, std::vector<unsigned char>>>;
inline const std::string kDataUriPrefix = "(data URI #";  // then its number and ")", as tinygltf messages show it
std::string extract_data_uris(const std::string& text, DataUris& uris);
// The decoded bytes for a path ending in one of those names, else null.
std::vector<unsigned char>* find_data_uri(DataUris& uris, const std::string& path);

// The files of one load, for tinygltf's file-system callbacks: everything is
// read through LoadOptions::read_file, so tests and fuzzers work from memory.
// Decoded data URIs are served under their stand-in names (extract_data_uris).
struct Files {
    const LoadOptions* options;
    std::string last_error;
    DataUris* data_uris = nullptr;
};
tinygltf::FsCallbacks file_callbacks(Files& files);
// tinygltf's image loader: images are kept encoded and decoded (through
// LoadOptions::decode_texture) only when a material uses them, with a
// message that names the use.
bool keep_encoded(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width, int height,
                  const unsigned char* bytes, int size, void* user);

// %XX escapes in a URI, as the glTF specification allows in relative paths;
// ok is false (and s returned) for a bad escape.
std::string percent_decode(const std::string& s, bool& ok);
// The path a relative URI names: decoded, beside `file`, lexically normal.
std::string uri_path(const std::string& file, const std::string& uri);

// The external files the document names, checked before tinygltf reads them,
// so that a missing buffer, or a URI that is not a relative path or a base64
// data URI, is reported by its glTF path and the path it resolves to. A
// missing image is a warning (returned): its textures are left out.
std::vector<std::string> check_uris(const nlohmann::json& doc, const std::string& file, const LoadOptions& options,
                                    DataUris& uris);

// EXT_meshopt_compression (gltf_meshopt.cpp). The decoded bytes of
// bufferViews[index] when it carries the extension (decoded once, kept in
// src.meshopt_views), else null. Every field is checked against the
// specification's rules and the decoded size is capped as accessors are
// (LoadOptions::max_triangles); corrupt or truncated data is an error naming
// the view.
const std::vector<unsigned char>* meshopt_view(const Source& src, int index);
// A buffer that only stands in for the uncompressed data of compressed views
// (marked "fallback": true, or given no data): it holds nothing to read.
bool is_fallback_buffer(const tinygltf::Buffer& buffer);
// Before tinygltf: each buffer without a uri that is a fallback (marked so,
// or named only by compressed views) gets a one-byte stand-in (a name in
// `uris`) and the fallback mark; tinygltf would otherwise refuse it, or read
// the GLB's binary chunk for it. True if the document changed.
bool stand_in_fallback_buffers(nlohmann::json& doc, bool binary, DataUris& uris);

// KHR_draco_mesh_compression (gltf_draco.cpp): a primitive's attributes
// decoded into the layout its accessors declare (tightly packed, of the
// accessor's component type: Draco's values converted with the accessor's
// `normalized`), and its triangles' corners.
struct DracoPrimitive {
    std::map<std::string, std::vector<unsigned char>> attributes;  // by glTF attribute name
    std::vector<std::uint32_t> corners;
};
// The decoded primitive when it carries the extension, else nothing.
std::optional<DracoPrimitive> decode_draco(const Source& src, const tinygltf::Primitive& p, const std::string& path);
// Before tinygltf: removes "indices" from each primitive that carries the
// extension (its triangles come from the Draco data; tinygltf refuses an
// indices accessor without a buffer view, as such files have). True if the
// document changed.
bool drop_draco_indices(nlohmann::json& doc);
// Points v (from view(), of the accessor of attribute `name`) at the decoded
// values when the extension holds that attribute.
void use_draco(const DracoPrimitive& d, const std::string& name, View& v);

// Materials and the textures they name: appends to model.materials and model.textures.
void read_materials(const Source& src, GltfModel& model);

}  // namespace clpath::gltf
