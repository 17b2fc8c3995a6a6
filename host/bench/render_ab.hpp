#pragma once
// clpath bench render-ab: the renderer's kernels against a variant of them
// (files replaced, build options added), in one process on one device. Both
// render the same scene with the same settings and seed into films of their
// own, one sample per pixel at a time, taking turns (which goes first
// alternates), so that a drift in the machine's speed weighs on both alike:
// what render-time noise hides between separate runs (a few per cent) shows
// in the pairs' ratios. Then the two images are compared pixel by pixel.
#include <cstdint>
#include <functional>
#include <string>

#include "bench/ab_ratios.hpp"
#include "cl/context.hpp"
#include "cl/embedded_sources.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct RenderAbOptions {
    std::uint32_t spp = 16;  // launch pairs: one sample per pixel each, after one warm-up sample
    std::uint32_t seed = 0;
    KernelVariant variant;   // files replaced, options added (may be empty with variant_shape)
    // Mega or Wavefront: the variant renders in this kernel shape and the
    // built-in kernels in the other; Auto: both in the device's default.
    KernelShape variant_shape = KernelShape::Auto;
};

struct RenderAbResult {
    std::string scene, device;
    int width = 0, height = 0;
    std::uint32_t spp = 0;
    std::string builtin_shape, variant_shape;  // the kernel shape each rendered in
    double builtin_msamples_per_s = 0, variant_msamples_per_s = 0;  // over all timed launches
    AbResult ab;             // differing: pixels whose mean differs in any channel
    double max_abs_diff = 0;  // largest difference of a channel's mean
};

// The scene's own render settings (as `clpath render SCENE` uses them), the
// seed from the options. Throws clpath::Error when a step fails, and for a
// variant whose files replace none of clpath's.
RenderAbResult run_render_ab(Context& ctx, const Scene& scene, const RenderAbOptions& options,
                             const std::function<void(const std::string&)>& log);

// "A/B: variant/built-in 1.03 (quartiles ...) over 16 launch pairs; built-in
// 0.95 Msamples/s, variant 0.98; images differ in 0 of 4096 pixels (largest
// difference 0)"
std::string describe_render_ab(const RenderAbResult& r);

}  // namespace clpath
