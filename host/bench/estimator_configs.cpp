#include "bench/estimator_configs.hpp"

#include <functional>
#include <map>

#include "util/error.hpp"

namespace clpath {

const std::vector<EstimatorConfig>& estimator_configs() {
    // The thesis renderer (docs/thesis-scene.md, after its source and the
    // thesis text): BSDF sampling only, diffuse bounces uniform over the hemisphere,
    // roulette by its depth rule, one bounding box per object.
    static const std::vector<EstimatorConfig> configs{
        {"thesis", "the thesis renderer's estimator",
         {{"integrator", "path-bsdf"}, {"hemisphere", "uniform"}, {"rr", "depth"}, {"accel", "flat"}}},
        {"cosine", "cosine-weighted hemisphere",
         {{"integrator", "path-bsdf"}, {"hemisphere", "cosine"}, {"rr", "depth"}, {"accel", "flat"}}},
        {"no-rr", "no Russian roulette",
         {{"integrator", "path-bsdf"}, {"hemisphere", "uniform"}, {"rr", "none"}, {"accel", "flat"}}},
        {"throughput-rr", "throughput Russian roulette",
         {{"integrator", "path-bsdf"}, {"hemisphere", "uniform"}, {"rr", "throughput"}, {"accel", "flat"}}},
        {"nee-mis", "next-event estimation with MIS",
         {{"integrator", "path"}, {"hemisphere", "uniform"}, {"rr", "depth"}, {"accel", "flat"}}},
        {"bvh", "BVH instead of one box per object",
         {{"integrator", "path-bsdf"}, {"hemisphere", "uniform"}, {"rr", "depth"}, {"accel", "bvh"}}},
        {"clpath", "clpath's default: NEE + MIS, cosine, throughput roulette, BVH",
         {{"integrator", "path"}, {"hemisphere", "cosine"}, {"rr", "throughput"}, {"accel", "bvh"}}},
    };
    return configs;
}

const std::vector<EstimatorConfig>& light_sampler_configs() {
    static const std::vector<EstimatorConfig> configs{
        // The two light samplers on clpath's default estimator (docs/light-bvh.md).
        {"lights-power", "clpath's default, lights picked in proportion to power",
         {{"integrator", "path"}, {"hemisphere", "cosine"}, {"rr", "throughput"}, {"accel", "bvh"},
          {"light-sampler", "power"}}},
        {"lights-bvh", "clpath's default, lights picked by the light BVH",
         {{"integrator", "path"}, {"hemisphere", "cosine"}, {"rr", "throughput"}, {"accel", "bvh"},
          {"light-sampler", "bvh"}}},
    };
    return configs;
}

std::vector<std::string> estimator_config_names() {
    std::vector<std::string> names;
    for (const auto& c : estimator_configs()) names.push_back(c.name);
    for (const auto& c : light_sampler_configs()) names.push_back(c.name);
    return names;
}

void apply_render_option(RenderSettings& s, const std::string& name, const std::string& value) {
    using Setter = std::function<void(RenderSettings&, const std::string&)>;
    static const std::map<std::string, Setter> setters{
        {"integrator", [](RenderSettings& r, const std::string& v) { r.integrator = parse_integrator(v); }},
        {"hemisphere", [](RenderSettings& r, const std::string& v) { r.hemisphere = parse_hemisphere(v); }},
        {"rr", [](RenderSettings& r, const std::string& v) { r.rr_rule = parse_rr_rule(v); }},
        {"accel", [](RenderSettings& r, const std::string& v) { r.accel = parse_accel(v); }},
        {"light-sampler", [](RenderSettings& r, const std::string& v) { r.light_sampler = parse_light_sampler(v); }},
    };
    const auto it = setters.find(name);
    if (it == setters.end()) throw Error("unknown render option '" + name + "'");
    it->second(s, value);
}

std::string describe_options(const std::vector<std::pair<std::string, std::string>>& options) {
    std::string s;
    for (const auto& [k, v] : options) s += (s.empty() ? "" : " ") + k + "=" + v;
    return s;
}

}  // namespace clpath
