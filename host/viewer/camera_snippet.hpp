#pragma once
// The camera as a scene-file snippet, to paste into a .json scene:
// {"camera": {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z], "vfov": deg, "resolution": [w,h]}}
#include <string>

#include "scene/scene.hpp"

namespace clpath::viewer {

// Numbers are written in their shortest form that reads back to the same float.
std::string camera_snippet(const Camera& camera);

}  // namespace clpath::viewer
