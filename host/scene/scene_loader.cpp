#include "scene/scene_loader.hpp"

#include "scene/builtin_scenes.hpp"

namespace clpath {

Scene load_scene(const std::string& spec) { return builtin_scene(spec); }

}  // namespace clpath
