#pragma once
// Scenes built in code, available without any file.
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

// The thesis renderer's Cornell box (shared/docs/thesis-scene.md), with every
// surface diffuse: the default scene.
Scene cornell_thesis_scene();

// Names accepted by builtin_scene(), and the scene for one of them (throws
// clpath::Error for an unknown name).
std::vector<std::string> builtin_scene_names();
Scene builtin_scene(const std::string& name);

}  // namespace clpath
