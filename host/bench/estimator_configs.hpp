#pragma once
// The estimator configurations the convergence benchmark compares: the thesis
// renderer's, the same with one choice changed at a time, and clpath's
// default. Each is data, a name and render options by the names
// `clpath render` uses, so adding one is one line.
#include <string>
#include <utility>
#include <vector>

#include "render/settings.hpp"

namespace clpath {

struct EstimatorConfig {
    std::string name;         // "thesis", "cosine", ...
    std::string description;  // what it changes, for tables
    std::vector<std::pair<std::string, std::string>> options;  // {"integrator", "path-bsdf"}, ...
};

// The standard list, the thesis configuration first (the baseline of the
// efficiency column).
const std::vector<EstimatorConfig>& estimator_configs();
// clpath's default with lights picked by power, then by the light BVH: run
// when named (--configs lights-power,lights-bvh), not by default.
const std::vector<EstimatorConfig>& light_sampler_configs();
// Both lists' names, the standard list's first.
std::vector<std::string> estimator_config_names();

// Sets one option by name; throws clpath::Error for an unknown name or a value
// the option does not accept.
void apply_render_option(RenderSettings& settings, const std::string& name, const std::string& value);

// "integrator=path-bsdf hemisphere=uniform rr=depth".
std::string describe_options(const std::vector<std::pair<std::string, std::string>>& options);

}  // namespace clpath
