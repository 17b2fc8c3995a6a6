#pragma once
// A scene file's mesh object with an "instances" list (docs/scene-format.md):
// the mesh is read once and placed by each entry's transform. Kept out of
// the scene file's reader so each file holds one job.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/json_fields.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"

namespace clpath {

// The entries of an "instances" list: each a transform, either
// {"translate", "rotate", "scale"} (as an object's "transform") or
// {"matrix": [12 or 16 numbers, row by row]} (an affine map; 16 numbers end
// in the row 0 0 0 1). Fails naming the entry and field for a wrong type, an
// empty list, a non-finite, non-affine or singular transform.
std::vector<glm::mat4> read_instance_transforms(const jsonf::Value& list);

// Why a mesh of these materials cannot be instanced (it emits: the light
// table lists flattened emitters only), or empty when it can.
std::string flattened_because(const Scene& scene, const std::vector<std::uint32_t>& materials);

// The mesh (vertices three per triangle, normals empty or parallel, one
// material per triangle, attributes each empty or parallel), first placed by
// `place` (the object's own transform), then by each of `transforms`. Kept
// once as an instanced mesh, with its attributes, unless it emits
// (flattened_because) or is placed once (walked faster flattened): then
// each copy is added flattened, and a note says why. Degenerate triangles
// (after `place`) are dropped, as SceneBuilder does.
void place_mesh_instances(Scene& scene, SceneBuilder& builder, const std::string& label,
                          const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                          const std::vector<std::uint32_t>& materials, const glm::mat4& place,
                          const std::vector<glm::mat4>& transforms, const VertexAttributes& attributes);

}  // namespace clpath
