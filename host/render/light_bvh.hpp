#pragma once
// A light BVH (Conty Estevez and Kulla 2018, "Importance sampling of many
// lights with adaptive tree splitting"; the design of pbrt-v4's
// BVHLightSampler): picks a light in proportion to an estimate of its
// contribution at a shading point, with the exact pmf of any given light for
// MIS. Built over the light table's finite lights; infinite lights (the
// environment, directional lights) are picked uniformly with probability
// n_infinite / (n_infinite + 1), the tree otherwise. docs/light-bvh.md.
//
// The sampling and pmf functions here are the host's reference of what the
// kernels compute, in float32 on the same compact nodes.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "shared_structs.h"

namespace clpath {

struct LightBvh {
    std::vector<LightBvhNode> nodes;  // node 0 is the root; empty when there is no finite light
    // Per light of the table: the path from the root to its leaf, bit d the
    // child taken at depth d (0: the first), with a 1 above the last step; 0
    // for a light not in the tree (infinite, or of zero power).
    std::vector<std::uint64_t> trail;
    std::vector<std::uint32_t> infinite;  // the infinite lights, picked uniformly
    glm::vec3 origin{0.0f}, scale{0.0f};  // world = origin + q * scale, per axis
    int depth = 0;                        // the deepest leaf's depth
};

// The depth limit the build keeps to (a trail is 64 bits).
constexpr int kLightBvhMaxDepth = 62;

LightBvh build_light_bvh(const std::vector<Light>& lights);

// A node's bounds, decoded.
struct LightBounds {
    glm::vec3 lo{0.0f}, hi{0.0f}, axis{0.0f, 0.0f, 1.0f};
    float power = 0, cos_theta_o = 1, cos_theta_e = 1;
    bool two_sided = false;
};
LightBounds decode_light_bounds(const LightBvh& bvh, const LightBvhNode& node);

// pbrt-v4's LightBounds::Importance: an estimate, conservative in angle, of
// what the node's lights give at p (normal n, or 0 for no surface).
float light_bounds_importance(const LightBounds& b, glm::vec3 p, glm::vec3 n);

struct LightPick {
    std::uint32_t light;
    float pmf;
};
// Picks a light for the point p (normal n) from u in [0, 1); none when every
// light the descent reaches gives nothing there.
std::optional<LightPick> sample_light_bvh(const LightBvh& bvh, glm::vec3 p, glm::vec3 n, float u);

// The probability that sample_light_bvh picks light at p, n: by its trail.
float light_bvh_pmf(const LightBvh& bvh, glm::vec3 p, glm::vec3 n, std::uint32_t light);

}  // namespace clpath
