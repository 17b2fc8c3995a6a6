// clpath bench render-ab: the renderer's kernels against a variant of them,
// launch by launch in one process (bench/render_ab.hpp).
#include <cstdio>
#include <memory>
#include <string>

#include "bench/render_ab.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/kernel_variant_option.hpp"
#include "cli/option_checks.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

struct RenderAbCliOptions {
    std::string scene, device, ab_kernels, ab_options, ab_shape;
    std::uint32_t spp = 16, seed = 0;
    int width = 0, height = 0;
    bool quick = false;
};

int run_render_ab_command(const RenderAbCliOptions& o) {
    if (o.ab_kernels.empty() && o.ab_options.empty() && o.ab_shape.empty())
        throw UsageError("bench render-ab: give the variant: --ab-kernels DIR, --ab-options OPTS, --ab-shape SHAPE "
                         "or several");
    RenderAbOptions ro;
    ro.spp = o.spp;
    ro.seed = o.seed;
    if (!o.ab_kernels.empty() || !o.ab_options.empty()) ro.variant = read_kernel_variant(o.ab_kernels, o.ab_options);
    if (!o.ab_shape.empty()) ro.variant_shape = parse_kernel_shape(o.ab_shape);
    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    if (o.quick) {
        scene.camera.width = 32;
        scene.camera.height = 24;
        ro.spp = 2;
    }
    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: bench render-ab '%s' (%zu triangles) at %dx%d, %u launch pairs of 1 spp\n",
                 scene.name.c_str(), scene.triangle_count(), scene.camera.width, scene.camera.height, ro.spp);
    RenderAbResult r;
    try {
        r = run_render_ab(ctx, scene, ro, [](const std::string& s) { std::fprintf(stderr, "clpath: %s\n", s.c_str()); });
    } catch (const Error& e) {
        throw Error(o.scene + ": " + e.what());
    }
    std::printf("scene: %s, %dx%d, device \"%s\"\n%s\n", r.scene.c_str(), r.width, r.height, r.device.c_str(),
                describe_render_ab(r).c_str());
    return 0;
}

}  // namespace

Command add_bench_render_ab_command(CLI::App& bench) {
    auto o = std::make_shared<RenderAbCliOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "render-ab",
        "The renderer's kernels against a variant of them in one process: both render the scene (its own settings), "
        "one sample per pixel at a time, taking turns; prints the median of the launch pairs' speed ratios with "
        "quartiles, and in how many pixels the two images differ");
    cmd->add_option("scene", o->scene, scene_argument_help())->required();
    add_kernel_variant_options(cmd, &o->ab_kernels, &o->ab_options, "the renderer's kernels",
                               "the variant's speed over the built-in kernels' and the pixels that differ are "
                               "printed (one of the two options is needed)");
    cmd->add_option("--ab-shape", o->ab_shape,
                    "The variant renders in this kernel shape (mega or wavefront) and the built-in kernels in the "
                    "other: the two shapes side by side")
        ->check(CLI::IsMember(std::vector<std::string>{"mega", "wavefront"}));
    cmd->add_option("--spp", o->spp, "Launch pairs (one sample per pixel each)")
        ->check(whole_number(1, 1u << 16))
        ->capture_default_str();
    cmd->add_option("--width", o->width, "Image width (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Image height (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--seed", o->seed, "Seed of both renders")->check(whole_number(0, 4294967294u))->capture_default_str();
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_flag("--quick", o->quick, "32x24 pixels, 2 launch pairs (for CI)");
    return [o] { return run_render_ab_command(*o); };
}

}  // namespace clpath
