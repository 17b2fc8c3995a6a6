#pragma once
// The parts of the glTF loader (gltf_model.hpp), shared between its files:
// checked accessor reads and the material and texture conversion.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_model.hpp"

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
    // Component c of element i as float (normalized integers mapped to [0,1] or [-1,1]).
    float get(std::size_t i, int c) const;
    // Element i of an index accessor.
    std::uint32_t index(std::size_t i) const;
};

// The accessor `index`, named `path` in messages, which must be of type
// `type` (TINYGLTF_TYPE_*, or any of two when alt_type >= 0) and of a
// component type in `allowed` (float ones are converted, integer ones only
// when normalized unless `integers` says they are indices).
View view(const Source& src, int index, const std::string& path, int type, int alt_type,
          const std::vector<int>& allowed, bool integers = false);

// Materials and the textures they name: appends to model.materials and model.textures.
void read_materials(const Source& src, GltfModel& model);

}  // namespace clpath::gltf
