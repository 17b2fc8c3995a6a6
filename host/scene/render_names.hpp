#pragma once
// The names of the render choices that scene files and the command line share:
// integrators, Russian roulette rules, hemisphere sampling. They live here, below
// render/, because a scene file's "render" block names them too.
#include <cstdint>
#include <string>
#include <vector>

#include "shared_structs.h"

namespace clpath {

// How diffuse surfaces choose the next direction (kernels/sampling.cl).
enum : std::uint32_t {
    kHemisphereCosine = 0,   // by cos theta / pi: the weight is the albedo (clpath's default)
    kHemisphereUniform = 1,  // uniformly over the hemisphere: the thesis text's estimator, kept for comparison
};

// Throw clpath::Error naming the valid choices for an unknown name.
std::uint32_t parse_integrator(const std::string& name);  // CLP_INTEGRATOR_*
std::uint32_t parse_rr_rule(const std::string& name);     // CLP_RR_*
std::uint32_t parse_hemisphere(const std::string& name);  // kHemisphere*
const char* integrator_name(std::uint32_t integrator);
const char* rr_rule_name(std::uint32_t rule);
const char* hemisphere_name(std::uint32_t hemisphere);
const std::vector<std::string>& integrator_names();  // "path", "path-bsdf", "ao", ...
const std::vector<std::string>& rr_rule_names();     // "none", "throughput", "depth"
const std::vector<std::string>& hemisphere_names();  // "cosine", "uniform"
// The light samplers (render/settings.hpp LightSampler, in this order).
const std::vector<std::string>& light_sampler_names();  // "auto", "power", "bvh"

}  // namespace clpath
