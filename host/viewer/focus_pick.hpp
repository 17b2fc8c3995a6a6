#pragma once
// Click to focus: the distance of the plane in focus that puts the surface
// under a pixel in focus. Plain C++ over the scene's triangles, no window.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath::viewer {

// The nearest triangle along the camera's central ray (the lens centre's)
// through image point (x, y) in pixels (x right, y down, (0, 0) the image's
// top-left corner): its distance along the view direction, the camera's
// focus distance that makes it sharp. Nothing hit (sky): nullopt.
// triangles: three vertices each, as Scene::vertices. A brute-force walk in
// double precision: a click is rare, and it needs no acceleration structure
// on the host (about 10 ms per million triangles).
std::optional<float> focus_distance_at(const std::vector<glm::vec3>& triangles, const Camera& camera, glm::vec2 pixel);

// Where a window pixel lands in an image drawn letterboxed into it:
// window (x, y down) to image pixels, or nullopt outside the image.
// rect: (x, y, width, height) of the image in the framebuffer, y up (as
// letterbox.hpp gives it); scale: framebuffer pixels per window pixel.
std::optional<glm::vec2> window_to_image(glm::vec2 window, glm::vec2 scale, glm::ivec2 framebuffer, glm::ivec4 rect,
                                         glm::ivec2 image);

}  // namespace clpath::viewer
