#include "render/settings.hpp"

#include <cstdlib>

#include "util/error.hpp"

namespace clpath {

const std::vector<std::string>& kernel_shape_names() {
    static const std::vector<std::string> names{"auto", "mega", "wavefront"};  // KernelShape
    return names;
}

KernelShape parse_kernel_shape(const std::string& name) {
    const auto& names = kernel_shape_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return KernelShape(i);
    throw Error("unknown kernel shape '" + name + "' (choose one of: auto, mega, wavefront)");
}

const char* kernel_shape_name(KernelShape shape) { return kernel_shape_names().at(std::size_t(shape)).c_str(); }

LightSampler parse_light_sampler(const std::string& name) {
    const auto& names = light_sampler_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return LightSampler(i);
    throw Error("unknown light sampler '" + name + "' (choose one of: auto, power, bvh)");
}

const char* light_sampler_name(LightSampler sampler) { return light_sampler_names().at(std::size_t(sampler)).c_str(); }

KernelShape resolve_kernel_shape(const RenderSettings& s, bool gpu) {
    const bool light_transport = s.integrator == CLP_INTEGRATOR_PATH || s.integrator == CLP_INTEGRATOR_PATH_BSDF;
    if (s.kernel_shape == KernelShape::Wavefront && !light_transport)
        throw Error(std::string("the wavefront kernels render the path and path-bsdf integrators; '") +
                    integrator_name(s.integrator) + "' renders one bounce, as the megakernel (--kernel mega or auto)");
    if (s.kernel_shape != KernelShape::Auto) return s.kernel_shape;
    // A user's (or a test sweep's) standing choice, where that shape renders the integrator.
    if (const char* env = std::getenv("CLPATH_KERNEL"); env && *env) {
        KernelShape shape;
        try {
            shape = parse_kernel_shape(env);
        } catch (const Error& e) {
            throw Error(std::string("CLPATH_KERNEL: ") + e.what());
        }
        if (shape == KernelShape::Mega || (shape == KernelShape::Wavefront && light_transport)) return shape;
    }
    // Measured (benchmarks/results/: bench render-ab --ab-shape on PoCL, the
    // GPU check on an NVIDIA H200): the megakernel is faster on PoCL, and on
    // the GPU neither shape wins on every scene, so the simpler one runs.
    (void)gpu;
    return KernelShape::Mega;
}

void validate_settings(const RenderSettings& s) {
    if (s.integrator >= CLP_INTEGRATOR_COUNT) throw Error("internal: unknown integrator");
    resolve_kernel_shape(s, false);  // the wavefront asked for an integrator it does not have
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
    s.light_sampler = parse_light_sampler(d.light_sampler);
    return s;
}

}  // namespace clpath
