#pragma once
// The lights next-event estimation samples: every emissive triangle, every
// punctual light and the environment in one table, with a Walker alias table
// that picks a light in proportion to its power in O(1).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/environment_map.hpp"
#include "render/kernel_features.hpp"
#include "scene/scene.hpp"
#include "shared_structs.h"

namespace clpath {

struct LightTable {
    std::vector<Light> lights;
    std::vector<AliasEntry> alias;                // parallel to lights
    std::vector<std::uint32_t> light_of_triangle;  // per scene triangle: its light, or CLP_NO_LIGHT
    std::uint32_t environment = CLP_NO_LIGHT;     // the environment's index
};

// Only the light kinds the features enable are entered. scene_radius bounds
// the scene: infinite lights' power is their flux through its disk (as pbrt).
LightTable build_light_table(const Scene& scene, const KernelFeatures& features, const EnvironmentMap& env,
                             float scene_radius);

// Vose's (1991) alias table for weights >= 0, not all zero; pmf = w / sum.
std::vector<AliasEntry> build_alias_table(const std::vector<double>& weights);

double luminance(glm::vec3 rgb);

}  // namespace clpath
