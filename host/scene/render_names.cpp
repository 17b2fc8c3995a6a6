#include "scene/render_names.hpp"

#include "util/error.hpp"

namespace clpath {
namespace {
std::uint32_t find_name(const std::vector<std::string>& names, const std::string& name, const char* what) {
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return std::uint32_t(i);
    std::string choices;
    for (const auto& n : names) choices += (choices.empty() ? "" : ", ") + n;
    throw Error("unknown " + std::string(what) + " '" + name + "' (choose one of: " + choices + ")");
}
}  // namespace

const std::vector<std::string>& integrator_names() {
    // Indexed by CLP_INTEGRATOR_*.
    static const std::vector<std::string> names{"path", "path-bsdf", "ao", "normals", "depth", "albedo", "heatmap"};
    static_assert(CLP_INTEGRATOR_COUNT == 7);
    return names;
}

const std::vector<std::string>& rr_rule_names() {
    static const std::vector<std::string> names{"none", "throughput", "depth"};  // CLP_RR_*
    return names;
}

const std::vector<std::string>& hemisphere_names() {
    static const std::vector<std::string> names{"cosine", "uniform"};  // kHemisphere*
    return names;
}

std::uint32_t parse_integrator(const std::string& name) { return find_name(integrator_names(), name, "integrator"); }
std::uint32_t parse_rr_rule(const std::string& name) {
    return find_name(rr_rule_names(), name, "Russian roulette rule");
}
std::uint32_t parse_hemisphere(const std::string& name) {
    return find_name(hemisphere_names(), name, "hemisphere sampling");
}
const char* integrator_name(std::uint32_t i) { return integrator_names().at(i).c_str(); }
const char* rr_rule_name(std::uint32_t r) { return rr_rule_names().at(r).c_str(); }
const char* hemisphere_name(std::uint32_t h) { return hemisphere_names().at(h).c_str(); }

const std::vector<std::string>& light_sampler_names() {
    static const std::vector<std::string> names{"auto", "power", "bvh"};
    return names;
}

}  // namespace clpath
