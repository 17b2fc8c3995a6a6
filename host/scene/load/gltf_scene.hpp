#pragma once
// glTF models into scenes: a bare .gltf/.glb as a whole scene, or placed as a
// mesh object of a scene file.
#include <cstdint>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "scene/load/gltf_model.hpp"
#include "scene/scene_builder.hpp"

namespace clpath {

// Adds the model's textures, the materials its triangles use, its triangles
// (one object per placed primitive, placed by `place` after the node
// hierarchy) and its lights. material_override, when set, gives the scene
// material for a glTF material index (-1: the default material), or returns
// UINT32_MAX to keep the model's own. smooth = false drops vertex normals.
void add_gltf(Scene& scene, SceneBuilder& builder, const GltfModel& model, const glm::mat4& place,
              const std::string& file, bool smooth = true,
              const std::function<std::uint32_t(int)>& material_override = {});

// A bare glTF file as a scene, in the default presentation of a bare mesh
// (presentation.hpp) for what the file lacks: its chosen camera, or one
// framing the model; its lights and emitters, or the ground, sky and sun.
Scene gltf_scene(const std::string& file, const LoadOptions& options = {});

}  // namespace clpath
