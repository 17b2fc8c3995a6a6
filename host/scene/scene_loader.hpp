#pragma once
// The one entry point that turns what a user names into a Scene: a built-in
// scene's name, a scene file (.json), or a bare mesh (.obj). The renderer, the
// viewer and the benchmarks all load through here.
#include <string>

#include "scene/scene.hpp"

namespace clpath {

// Throws clpath::Error naming the file and the line or field at fault.
Scene load_scene(const std::string& spec);

}  // namespace clpath
