#pragma once
// A glTF primitive written back as gltfpack quantises by default, for the
// tests that check KHR_mesh_quantization and KHR_texture_transform against the
// unquantised original: positions as plain uint16 on one grid for all axes
// that the node's scale and translation map back, normals as normalised int8,
// texture coordinates as normalised uint16 that a KHR_texture_transform offset
// and scale map back; without indices (one vertex per corner, as the loader
// returns them).
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scene/load/gltf_model.hpp"

namespace clpath::test {

struct QuantisedGltf {
    nlohmann::json doc;  // refers to its buffer as bin_uri
    std::string bin;
    glm::vec3 lo{0};           // the grid's origin (the node's translation)
    float step = 0;            // the grid's step (the node's scale)
    float extent = 0;          // the largest side of the bounding box
    glm::vec2 uv_lo{0}, uv_scale{1};  // the texture transform's offset and scale
};

// image_uris: the material's base-colour texture and, if given, its
// metallic-roughness texture, each with the transform.
QuantisedGltf quantise_like_gltfpack(const GltfPrimitive& p, const std::vector<std::string>& image_uris,
                                     const std::string& bin_uri);

}  // namespace clpath::test
