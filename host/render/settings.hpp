#pragma once
// How to render, apart from what: integrator, depth, roulette, seed, BVH
// options. The names of the choices are in scene/render_names.hpp.
//
// Where each setting lives: a scene file's "render" block holds the scene's
// defaults (SceneRenderDefaults, read once by settings_from_scene); the
// command line and the viewer override a RenderSettings, never the scene.
// From here the kernels get the integrator and the maximum depth as build
// options (render/kernel_features.hpp: CLP_INTEGRATOR, CLP_MAX_DEPTH), the
// rest per launch in FrameParams. How many samples, for how long and in what
// chunks are the render session's (render/render_session.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"
#include "scene/render_names.hpp"
#include "scene/scene.hpp"
#include "shared_structs.h"

namespace clpath {

// The shape of the path tracer's kernels: one kernel per path
// (kernels/integrator.cl), or the wavefront of small kernels over queues of
// paths (kernels/wavefront.cl). Auto takes the one measured faster on the
// device's kind (resolve_kernel_shape).
enum class KernelShape : std::uint32_t { Auto, Mega, Wavefront };
KernelShape parse_kernel_shape(const std::string& name);  // clpath::Error naming the choices
const char* kernel_shape_name(KernelShape shape);
const std::vector<std::string>& kernel_shape_names();    // "auto", "mega", "wavefront"

// How next-event estimation picks a light: in proportion to power (an alias
// table), or by the light BVH's estimate of each light's contribution at the
// shading point (render/light_bvh.hpp). Auto takes the light BVH for scenes
// with many finite lights spread over the scene (SceneFeatures::many_lights),
// and power otherwise; under Auto the
// environment variable CLPATH_LIGHT_SAMPLER=power|bvh replaces that choice
// (the test suite runs its agreement tests again with bvh).
enum class LightSampler : std::uint32_t { Auto, Power, Bvh };
LightSampler parse_light_sampler(const std::string& name);  // clpath::Error naming the choices
const char* light_sampler_name(LightSampler sampler);  // light_sampler_names() (scene/render_names.hpp) lists them

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
    KernelShape kernel_shape = KernelShape::Auto;
    LightSampler light_sampler = LightSampler::Auto;
};

// Throws clpath::Error for settings no render can use (the depth roulette rule
// with no bounce, say).
void validate_settings(const RenderSettings& settings);

// The shape a render takes on a device: Auto becomes the shape measured
// faster on that kind of device (README, "Kernel shapes"), today the
// megakernel on CPUs (PoCL) and on GPUs (an NVIDIA H200) alike.
// Only the light-transport integrators (path, path-bsdf) have a wavefront
// shape: the one-bounce views (ao, normals, ...) run as the megakernel under
// Auto, and asking for the wavefront with them is an error. Under Auto, the
// environment variable CLPATH_KERNEL=mega|wavefront|auto replaces the
// device's default wherever that shape renders the integrator (the test
// suite runs its agreement tests again with CLPATH_KERNEL=wavefront).
KernelShape resolve_kernel_shape(const RenderSettings& settings, bool gpu);

// The settings a scene file asks for (its "render" block).
RenderSettings settings_from_scene(const SceneRenderDefaults& defaults);

}  // namespace clpath
