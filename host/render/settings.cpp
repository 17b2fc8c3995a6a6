#include "render/settings.hpp"

#include "util/error.hpp"

namespace clpath {

void validate_settings(const RenderSettings& s) {
    if (s.integrator >= CLP_INTEGRATOR_COUNT) throw Error("internal: unknown integrator");
    if (s.rr_rule == CLP_RR_DEPTH && s.max_depth < 1)
        throw Error("the depth Russian roulette rule needs a maximum depth of at least 1");
}

RenderSettings settings_from_scene(const SceneRenderDefaults& d) {
    RenderSettings s;
    s.integrator = parse_integrator(d.integrator);
    s.rr_rule = parse_rr_rule(d.russian_roulette);
    s.max_depth = d.max_depth;
    s.seed = d.seed;
    s.ao_distance = d.ao_distance;
    return s;
}

}  // namespace clpath
