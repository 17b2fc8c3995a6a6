#pragma once
// The one entry point that turns what a user names into a Scene: a built-in
// scene's name (builtin_scenes.hpp, including "scaling:N"), a scene file
// (.json, scene_file.hpp), or a bare mesh (.obj). The renderer, the viewer and
// the benchmarks all load through here.
#include <string>

#include "scene/load/load_options.hpp"
#include "scene/scene.hpp"

namespace clpath {

// Throws clpath::Error naming the file and the line or field at fault. The
// scene's warnings (Scene::warnings) are for the caller to show.
Scene load_scene(const std::string& spec, const LoadOptions& options = {});

}  // namespace clpath
