#pragma once
// The images an OBJ material maps (map_Kd, map_d), decoded into a scene's
// texture list: one RGBA texture per material, colour from map_Kd, alpha from
// map_d's first channel (or map_Kd's own alpha when map_d names the same file).
#include "scene/load/load_options.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/scene.hpp"

namespace clpath {

// om.material with its base texture slot set, the texture appended to
// scene.textures; om.material unchanged when it maps nothing. Throws
// clpath::Error naming the .mtl's image that is missing or undecodable.
SceneMaterial obj_material_with_textures(Scene& scene, const ObjMaterial& om, const LoadOptions& options);

}  // namespace clpath
