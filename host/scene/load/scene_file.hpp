#pragma once
// The JSON scene format (docs/scene-format.md): camera, render settings,
// named materials, objects (built-in shapes and OBJ meshes), punctual lights
// and an environment. Strict: an unknown field, a wrong type or a value out
// of range is an error naming the file and the field's path.
#include <string>

#include "scene/load/load_options.hpp"
#include "scene/scene.hpp"

namespace clpath {

// text is the file's contents; file names it in messages, and relative paths
// inside it are relative to its folder.
Scene parse_scene_file(const std::string& text, const std::string& file, const LoadOptions& options = {});

// A bare OBJ as a scene: its MTL materials (grey diffuse where it names none)
// in the default presentation (scene/presentation.hpp): camera, ground, sky, sun.
Scene obj_scene(const std::string& file, const LoadOptions& options = {});

}  // namespace clpath
