#pragma once
// Command-line overrides of what a scene brings: --camera and --env.
#include <string>

#include "scene/scene.hpp"

namespace clpath {

// "from=x,y,z;to=x,y,z;fov=deg;up=x,y,z;aperture=radius;focus=distance", any
// of the fields, in any order:
// the ones given replace the camera's. Throws clpath::UsageError naming the
// field and what it accepts.
Camera apply_camera_option(const std::string& text, Camera camera);

// "R,G,B" or one grey value (constant radiance, finite and >= 0), or the path
// of an equirectangular image (.hdr, .exr). Throws clpath::UsageError.
Environment parse_env_option(const std::string& text);

}  // namespace clpath
