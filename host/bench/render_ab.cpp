#include "bench/render_ab.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/renderer.hpp"
#include "util/error.hpp"

namespace clpath {

RenderAbResult run_render_ab(Context& ctx, const Scene& scene, const RenderAbOptions& o,
                             const std::function<void(const std::string&)>& log) {
    if (o.variant.empty() && o.variant_shape == KernelShape::Auto)
        throw Error("bench render-ab: no variant (give --ab-kernels, --ab-options or --ab-shape)");
    if (o.spp < 1) throw Error("bench render-ab: at least 1 sample per pixel");
    RenderSettings settings = settings_from_scene(scene.render);
    settings.seed = o.seed;
    RenderAbResult r;
    r.scene = scene.name;
    r.device = ctx.device().describe();
    r.width = scene.camera.width;
    r.height = scene.camera.height;
    r.spp = o.spp;
    if (log) log("compiling and uploading for " + r.device);
    const std::shared_ptr<const PreparedScene> prepared = prepare_scene(scene, settings);
    RenderSettings variant_settings = settings;
    if (o.variant_shape != KernelShape::Auto) {
        variant_settings.kernel_shape = o.variant_shape;
        settings.kernel_shape = o.variant_shape == KernelShape::Mega ? KernelShape::Wavefront : KernelShape::Mega;
    }
    r.builtin_shape = kernel_shape_name(resolve_kernel_shape(settings, ctx.device().is_gpu));
    r.variant_shape = kernel_shape_name(resolve_kernel_shape(variant_settings, ctx.device().is_gpu));
    Renderer renderers[2] = {Renderer(ctx, *prepared, settings), Renderer(ctx, *prepared, variant_settings, o.variant)};
    for (Renderer& rd : renderers) {
        rd.add_samples(1);  // warm-up: a device may finish compiling at the first launch
        rd.reset();
    }
    double total[2] = {0, 0};
    for (std::uint32_t s = 0; s < o.spp; ++s) {
        double t[2] = {0, 0};
        for (int j = 0; j < 2; ++j) {
            const int which = int((s + std::uint32_t(j)) % 2);
            const double before = renderers[which].stats().render_seconds;
            renderers[which].add_samples(1);
            t[which] = renderers[which].stats().render_seconds - before;
        }
        total[0] += t[0];
        total[1] += t[1];
        if (t[1] > 0) r.ab.ratios.push_back(t[0] / t[1]);
    }
    if (r.ab.ratios.empty()) throw Error("bench render-ab: the launches took no measurable time");
    finish_ab(r.ab);
    const double samples = double(o.spp) * r.width * r.height;
    r.builtin_msamples_per_s = total[0] > 0 ? samples / total[0] * 1e-6 : 0;
    r.variant_msamples_per_s = total[1] > 0 ? samples / total[1] * 1e-6 : 0;
    const Image a = renderers[0].resolve(1.0f).linear, b = renderers[1].resolve(1.0f).linear;
    for (std::size_t p = 0; p < a.rgb.size() / 3; ++p) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            const float x = a.rgb[3 * p + c], y = b.rgb[3 * p + c];
            if (x == y) continue;
            differs = true;
            // NaN in either is a difference as large as it gets.
            const double d = std::fabs(double(x) - double(y));
            r.max_abs_diff = std::isnan(d) ? INFINITY : std::max(r.max_abs_diff, d);
        }
        r.ab.differing += differs;
    }
    return r;
}

std::string describe_render_ab(const RenderAbResult& r) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "; built-in (%s) %.3f Msamples/s, variant (%s) %.3f; images differ in %zu of %zu pixels (largest "
                  "difference %.3g)",
                  r.builtin_shape.c_str(), r.builtin_msamples_per_s, r.variant_shape.c_str(), r.variant_msamples_per_s,
                  r.ab.differing,
                  std::size_t(r.width) * std::size_t(r.height), r.max_abs_diff);
    return "A/B: " + describe_ab_ratios(r.ab) + buf;
}

}  // namespace clpath
