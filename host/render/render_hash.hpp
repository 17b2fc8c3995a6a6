#pragma once
// A fingerprint of everything that decides a render's pixels: the scene's
// geometry, materials, lights, environment and camera, and the settings. Ranks
// of an MPI job compare it before rendering, and a checkpoint carries it, so
// that sums of different renders are never added together.
#include <cstdint>

#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

std::uint64_t render_hash(const Scene& scene, const RenderSettings& settings);

}  // namespace clpath
