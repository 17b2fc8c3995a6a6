#pragma once
// How to render, apart from what: integrator, depth, roulette, seed, BVH
// options. Names here are the ones the command line and scene files use.
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"
#include "scene/scene.hpp"
#include "shared_structs.h"

namespace clpath {

// How diffuse surfaces choose the next direction (kernels/sampling.cl).
enum : std::uint32_t {
    kHemisphereCosine = 0,   // by cos theta / pi: the weight is the albedo (clpath's default)
    kHemisphereUniform = 1,  // uniformly over the hemisphere: the thesis text's estimator, kept for comparison
};

struct RenderSettings {
    std::uint32_t integrator = CLP_INTEGRATOR_PATH;
    std::uint32_t max_depth = 16;  // bounces; 0 shows emitters only
    std::uint32_t rr_rule = CLP_RR_THROUGHPUT;
    std::uint32_t rr_min_depth = 3;  // bounces before throughput roulette starts
    std::uint32_t hemisphere = kHemisphereCosine;
    std::uint32_t seed = 0;
    float ao_distance = 0;  // ambient occlusion ray length; 0: a tenth of the scene's diagonal
    // Compile every feature in, whatever the scene uses (for measuring what
    // specialisation gains, and for testing that it changes nothing).
    bool all_features = false;
    // Launches are sized to take about this long: short enough for a GPU
    // driver's watchdog and an interactive viewer, long enough to keep a device busy.
    double target_launch_seconds = 0.1;
    BvhBuildOptions bvh;
    // The acceleration structure: the BVH, or the thesis renderer's one box
    // per object (the baseline of the benchmarks). Fixed for a Renderer's life.
    Accel accel = Accel::Bvh;
};

// Throw clpath::Error naming the valid choices for an unknown name.
std::uint32_t parse_integrator(const std::string& name);
std::uint32_t parse_rr_rule(const std::string& name);
std::uint32_t parse_hemisphere(const std::string& name);
const char* integrator_name(std::uint32_t integrator);
const char* rr_rule_name(std::uint32_t rule);
const char* hemisphere_name(std::uint32_t hemisphere);
const std::vector<std::string>& integrator_names();  // "path", "path-bsdf", "ao", ...
const std::vector<std::string>& rr_rule_names();
const std::vector<std::string>& hemisphere_names();  // "cosine", "uniform"

// The settings a scene file asks for (its "render" block).
RenderSettings settings_from_scene(const SceneRenderDefaults& defaults);

}  // namespace clpath
