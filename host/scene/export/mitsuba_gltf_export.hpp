#pragma once
// The glTF metallic-roughness material (CLP_MAT_GLTF) and its textures as
// Mitsuba 3 objects, for scene/mitsuba_export.*:
//   metallic 1 everywhere, alpha >= 1e-3 everywhere
//                -> principled, metallic 1 (Schlick F0 = base colour, GGX
//                   alpha = roughness^2; Mitsuba's Smith masking is separable,
//                   clpath's height-correlated), as the conductor is exported
//   otherwise    -> gltf_metallic_roughness, a plugin the reference script
//                   registers (benchmarks/references/gltf_bsdf.py): the same
//                   model written from the glTF specification's formulas
//   both wrapped in twosided; a normal map in Mitsuba's normalmap inside it,
//   one for each face (its frame, tangent = dp/du, bitangent = n x tangent,
//   is clpath's for UVs that are not mirrored and meshes without stored
//   tangents: others are refused); alpha MASK in mask with a threshold
//   texture (the script's), BLEND in mask.
// Textures become bitmap textures with clpath's filter and wrap mode; their
// texels go out as raw files (stem-texN.rgba8: 4 bytes a texel, row 0 at the
// top; .rgba32f: 4 floats) and the script decodes sRGB where clpath does,
// picks the channel (metallic B, roughness G, coverage A) and multiplies the
// material's factor in ("clpath_texture" markers).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

struct MitsubaTextureFiles {
    std::string stem;
    std::map<int, std::string> written;                      // texture index -> file name
    std::vector<std::pair<std::string, std::string>> files;  // file name, bytes
};

// The BSDF dictionary (JSON) for material `mi` of the scene, which must be
// CLP_MAT_GLTF; its base colour times the vertex colours when `colours`.
// Throws clpath::Error for what Mitsuba cannot be given the same way (wrap
// modes that differ between the axes, a normal map on mirrored UVs or with
// stored tangents, normal maps without texture coordinates).
std::string mitsuba_gltf_bsdf(const Scene& scene, std::uint32_t mi, const std::string& name, MitsubaTextureFiles& tex,
                              bool colours);

// `texture` (JSON) times the mesh's vertex colours: the script's product
// texture with a mesh_attribute ("vertex_color", which the script adds to
// the shape from the shape's "clpath_vertex_colors" file: RGB floats per
// corner, in the OBJ's vertex order).
std::string mitsuba_vertex_colour_product(const std::string& texture);

// The area light's radiance (JSON): the emission factor, times the emission
// texture where the material has one.
std::string mitsuba_gltf_radiance(const Scene& scene, const SceneMaterial& m, MitsubaTextureFiles& tex);

// Whether the material's alpha mode makes Mitsuba see through it somewhere
// (mask): the scene then needs the volpath integrator, whose shadow rays pass
// such surfaces (path's stop at them).
bool mitsuba_gltf_has_cutout(const SceneMaterial& m);

// MASK with a constant coverage below the cutoff: clpath never hits it.
bool mitsuba_gltf_invisible(const SceneMaterial& m);

}  // namespace clpath
