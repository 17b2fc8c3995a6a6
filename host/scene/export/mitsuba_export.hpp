#pragma once
// A scene as Mitsuba 3 renders it: a scene dictionary (the argument of
// mitsuba.load_dict) written as JSON, and one Wavefront OBJ mesh per material.
// benchmarks/references/mitsuba_reference.py loads the two and renders the
// reference images. Each clpath model maps onto the Mitsuba plugin that
// computes the same thing; where none does exactly, the closest one is named
// in the JSON ("clpath_notes") and in benchmarks/references/README.md:
//   diffuse      -> twosided(diffuse)
//   mirror       -> twosided(conductor, material "none": Fresnel 1, tinted)
//   conductor    -> twosided(principled, metallic 1): Schlick Fresnel with
//                   F0 = colour, GGX alpha = roughness^2 (Mitsuba's Smith
//                   masking is separable, clpath's height-correlated)
//   dielectric   -> dielectric / roughdielectric (GGX, alpha = roughness^2),
//                   ext_ior 1, tint = specular_transmittance
//   emission     -> area (one-sided); a two-sided emitter gets a second,
//                   back-facing copy of its triangles behind the first
//   point, directional -> point, directional
//   spot         -> spot with a falloff texture (clpath's smoothstep in cos)
//   environment  -> constant, or envmap rotated to clpath's orientation
//   glTF material, textures -> scene/mitsuba_gltf_export.hpp; texture
//                   coordinates go into the OBJ files (flip_tex_coords off);
//                   with alpha cut-outs the integrator is volpath (its shadow
//                   rays pass masked surfaces; path's stop at them)
//   vertex colours -> a file of RGB floats per corner beside the mesh, which
//                   the script adds to the shape as "vertex_color"; the
//                   diffuse albedo or glTF base colour is multiplied by it
//                   (other kinds, emitters and vertex alpha are refused)
// Markers the script turns into Mitsuba objects start with "clpath_".
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

struct MitsubaExport {
    std::string json;                                        // the scene dictionary
    std::vector<std::pair<std::string, std::string>> meshes;    // file name (beside the JSON), OBJ text
    std::vector<std::pair<std::string, std::string>> textures;  // file name (beside the JSON), raw texels or colours
};

// stem: the shared file name without folder or extension; the meshes are
// stem-<material>.obj. Throws clpath::Error for a scene without triangles.
MitsubaExport export_mitsuba_scene(const Scene& scene, const std::string& stem, const std::string& source);

}  // namespace clpath
