#pragma once
// The parts of the glTF loader (gltf_model.hpp), shared between its files:
// checked accessor reads and the material and texture conversion.
#include <cstddef>
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
};

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

// Materials and the textures they name: appends to model.materials and model.textures.
void read_materials(const Source& src, GltfModel& model);

}  // namespace clpath::gltf
