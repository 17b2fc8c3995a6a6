#include <cctype>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/option_checks.hpp"
#include "cli/progress.hpp"
#include "cli/scene_overrides.hpp"
#include "image/image.hpp"
#include "image/tone_map.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/scene_loader.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// Options left unset (nullopt) take the scene file's value, then the default.
struct RenderOptions {
    std::string scene = "cornell";
    std::optional<std::uint64_t> spp;
    double time_limit = 0;
    std::optional<std::uint32_t> max_depth, seed;
    std::uint32_t rr_min_depth = 3;
    std::optional<std::string> rr, integrator;
    std::string hemisphere = "cosine";
    std::optional<float> ao_distance;
    bool all_features = false;
    int width = 0, height = 0;
    std::vector<std::string> outputs;
    std::string device;
    int leaf_size = 4, bins = 16;
    bool quiet = false;
    std::string accel = "bvh";
    float exposure = 0;
    std::string tonemap = "clamp";
    std::optional<std::string> camera, env;
    bool no_ground = false, no_partial = false;
};

bool is_bare_mesh(const std::string& spec) {
    std::string ext = std::filesystem::path(spec).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

int run_render(const RenderOptions& o) {
    // Everything that can be checked before rendering is checked first.
    const auto load_start = std::chrono::steady_clock::now();
    LoadOptions load;
    load.presentation.ground = !o.no_ground;
    if (o.env) load.presentation.environment = parse_env_option(*o.env);
    if (o.no_ground && !is_bare_mesh(o.scene))
        std::fprintf(stderr, "clpath: warning: --no-ground has no effect on %s: only a bare mesh gets a ground\n",
                     o.scene.c_str());
    Scene scene = load_scene(o.scene, load);
    if (load.presentation.environment) scene.environment = *load.presentation.environment;
    if (o.camera) scene.camera = apply_camera_option(*o.camera, scene.camera);
    DisplaySettings display;
    display.exposure_stops = o.exposure;
    display.tone_map = parse_tone_map(o.tonemap);
    const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    if (!o.quiet)
        std::fprintf(stderr, "clpath: loaded '%s' from %s in %.3f s: %zu triangles, %zu materials\n", scene.name.c_str(),
                     o.scene.c_str(), load_seconds, scene.triangle_count(), scene.materials.size());
    if (o.spp) scene.render.spp = std::uint32_t(std::min<std::uint64_t>(*o.spp, kMaxSamplesPerPixel));
    if (o.max_depth) scene.render.max_depth = *o.max_depth;
    if (o.seed) scene.render.seed = *o.seed;
    if (o.rr) scene.render.russian_roulette = *o.rr;
    if (o.integrator) scene.render.integrator = *o.integrator;
    if (o.ao_distance) scene.render.ao_distance = *o.ao_distance;
    RenderSettings settings = settings_from_scene(scene.render);
    settings.rr_min_depth = o.rr_min_depth;
    settings.hemisphere = parse_hemisphere(o.hemisphere);
    settings.all_features = o.all_features;
    settings.bvh.max_leaf_size = o.leaf_size;
    settings.bvh.bins = o.bins;
    settings.accel = parse_accel(o.accel);
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    std::vector<std::string> outputs = o.outputs;
    if (outputs.empty()) {
        // The default destination is created; one the user names must exist.
        std::filesystem::create_directories("out");
        outputs = {"out/" + scene.name + ".png", "out/" + scene.name + ".exr"};
    }
    for (const auto& out : outputs) check_output_path(out);
    // --time alone renders until the time is up; --spp with it caps the samples.
    const std::uint64_t spp = o.spp ? *o.spp : (o.time_limit > 0 ? 0 : scene.render.spp);
    if (!scene.has_emitter())
        std::fprintf(stderr, "clpath: warning: scene '%s' has no emitter; the image will be black\n",
                     scene.name.c_str());

    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    if (!o.quiet)
        std::fprintf(stderr, "clpath: rendering '%s' (%zu triangles) at %dx%d with '%s' on %s\n", scene.name.c_str(),
                     scene.triangle_count(), scene.camera.width, scene.camera.height,
                     integrator_name(settings.integrator), device.describe().c_str());
    // A scene too large for the device is found here, before any allocation;
    // the message then names the scene it is about.
    std::unique_ptr<Renderer> renderer_ptr;
    try {
        renderer_ptr = std::make_unique<Renderer>(ctx, scene, settings);
    } catch (const Error& e) {
        throw Error(o.scene + ": " + e.what());
    }
    Renderer& renderer = *renderer_ptr;
    if (!o.quiet)
        std::fprintf(stderr, "clpath: %s; kernels %s in %.2f s\n", describe(renderer.bvh_stats()).c_str(),
                     renderer.compiled_from_cache() ? "loaded from cache" : "compiled", renderer.compile_seconds());

    Progress progress(spp, o.time_limit, !o.quiet);
    // From here Ctrl-C or SIGTERM stops after the current pass (about a second
    // at most) and the samples so far are written, unless --no-partial.
    InterruptGuard interrupt;
    const auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    double seconds_per_sample = 0;  // measured on the way
    for (;;) {
        const std::uint64_t done = renderer.stats().samples_per_pixel;
        if (InterruptGuard::requested()) break;
        if (spp && done >= spp) break;
        if (o.time_limit > 0 && elapsed() >= o.time_limit) break;
        // One sample per step when a time limit is set, so the limit is kept closely;
        // otherwise steps of up to 1/20 of the total, for a smooth progress bar,
        // and of about a second at most, so that progress is reported often.
        std::uint64_t step = o.time_limit > 0 ? 1 : std::max<std::uint64_t>(1, spp / 20);
        // The first pass is one sample: it measures how long one takes.
        step = seconds_per_sample > 0
                   ? std::min(step, std::max<std::uint64_t>(1, std::uint64_t(1.0 / seconds_per_sample)))
                   : 1;
        if (spp) step = std::min(step, spp - done);
        if (done + step > kMaxSamplesPerPixel) break;
        const double before = elapsed();
        renderer.add_samples(std::uint32_t(step));
        const double after = elapsed();
        seconds_per_sample = (after - before) / double(step);
        progress.update(renderer.stats().samples_per_pixel, after);
    }
    progress.finish();
    const double wall = elapsed();
    const int signal = InterruptGuard::requested();
    // The shell's convention for a program ended by a signal: 128 + its number.
    const int exit_status = signal ? 128 + signal : 0;
    if (signal && (o.no_partial || renderer.stats().samples_per_pixel == 0)) {
        std::fprintf(stderr, "clpath: interrupted (%s) after %llu samples per pixel; nothing written%s\n",
                     signal == SIGINT ? "SIGINT" : "SIGTERM", (unsigned long long)renderer.stats().samples_per_pixel,
                     o.no_partial ? " (--no-partial)" : "");
        return exit_status;
    }
    if (signal && !o.quiet)
        std::fprintf(stderr, "clpath: interrupted (%s): writing the image of the %llu samples per pixel so far\n",
                     signal == SIGINT ? "SIGINT" : "SIGTERM", (unsigned long long)renderer.stats().samples_per_pixel);
    RenderedImage image = renderer.resolve();
    // PNG gets the display transform; EXR and PFM keep the linear radiance.
    if (!display.is_identity()) image.srgb8 = display_srgb8(image.linear, display);
    for (const auto& out : outputs) {
        write_image(out, image);
        if (!o.quiet) std::fprintf(stderr, "clpath: wrote %s\n", out.c_str());
    }

    const RenderStats& st = renderer.stats();
    const double samples = double(st.samples_per_pixel) * scene.camera.width * scene.camera.height;
    std::printf(
        "summary: device=\"%s\" integrator=%s triangles=%zu bvh_build_ms=%.2f bvh_nodes=%zu bvh_sah=%.2f spp=%llu "
        "render_s=%.3f msamples_per_s=%.3f mrays_per_s=%.3f rays=%llu nonfinite=%llu accel=%s interrupted=%d\n",
        device.name.c_str(), integrator_name(settings.integrator), renderer.triangle_count(), renderer.bvh_stats().build_ms, renderer.bvh_stats().node_count,
        renderer.bvh_stats().sah_cost, (unsigned long long)st.samples_per_pixel, wall, samples / wall * 1e-6,
        double(st.rays) / wall * 1e-6, (unsigned long long)st.rays, (unsigned long long)st.nonfinite,
        accel_name(settings.accel), signal ? 1 : 0);
    if (st.nonfinite)
        std::fprintf(stderr, "clpath: warning: %llu samples were NaN or infinite and were dropped\n",
                     (unsigned long long)st.nonfinite);
    return exit_status;
}

}  // namespace

Command add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene progressively and write the image");
    std::string names;
    for (const auto& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    cmd->add_option("scene", o->scene, "Scene file (.json), mesh (.obj) or built-in scene (" + names + ")")
        ->capture_default_str();
    cmd->add_option("--spp", o->spp, "Samples per pixel (default: the scene's, else 64; unlimited with --time)")
        ->check(whole_number(1, kMaxSamplesPerPixel));
    cmd->add_option("--time", o->time_limit, "Stop after this many seconds")->check(real_number(0, 31536000, true));
    cmd->add_option("--max-depth", o->max_depth, "Maximum bounces (0: emitters only; default 16)")
        ->check(whole_number(0, 1024));
    cmd->add_option("--rr", o->rr, "Russian roulette: throughput (default, unbiased), depth (the thesis rule), none")
        ->check(CLI::IsMember(rr_rule_names()));
    cmd->add_option("--integrator,-i", o->integrator, "Integrator: path (default: NEE + MIS), path-bsdf, ao, "
                    "or a debug view: normals, depth, albedo, heatmap")
        ->check(CLI::IsMember(integrator_names()));
    cmd->add_option("--hemisphere", o->hemisphere,
                    "Diffuse bounces: cosine (default, cos/pi-weighted) or uniform (the thesis text's estimator)")
        ->check(CLI::IsMember(hemisphere_names()))
        ->capture_default_str();
    cmd->add_option("--ao-distance", o->ao_distance, "Ambient occlusion ray length (default: 1/10 of the scene size)")
        ->check(real_number(0, 1e9, true));
    cmd->add_flag("--all-features", o->all_features,
                  "Compile every material, light and integrator feature in (for comparison with the specialised kernels)");
    cmd->add_option("--rr-min-depth", o->rr_min_depth, "Bounces before throughput roulette starts")
        ->check(whole_number(0, 1024))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Random seed (default 0)")->check(whole_number(0, 4294967295u));
    cmd->add_option("--width", o->width, "Image width (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Image height (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--out,-o", o->outputs,
                    "Output image, .png (8-bit sRGB), .exr or .pfm (linear float); repeatable "
                    "(default: out/SCENE.png and out/SCENE.exr, the folder out/ created)");
    cmd->add_option("--exposure", o->exposure, "PNG only: brighten by this many stops (radiance x 2^stops)")
        ->check(real_number(-20, 20))
        ->capture_default_str();
    cmd->add_option("--tonemap", o->tonemap,
                    "PNG only: clamp (clip at white), reinhard (L/(1+L) on luminance) or aces (Narkowicz's "
                    "fitted ACES filmic curve); EXR and PFM stay linear")
        ->check(CLI::IsMember(tone_map_names()))
        ->capture_default_str();
    cmd->add_option("--camera", o->camera,
                    "Camera override, any of 'from=X,Y,Z;to=X,Y,Z;fov=DEGREES;up=X,Y,Z' (quote it: ';' is a "
                    "shell separator)");
    cmd->add_option("--env", o->env,
                    "Environment override: a colour R,G,B (or one grey value) or an equirectangular .hdr/.exr "
                    "image; for a bare mesh it replaces the default sky and sun");
    cmd->add_flag("--no-ground", o->no_ground, "A bare mesh gets no ground plane");
    cmd->add_option("--device,-d", o->device,
                    "OpenCL device: cpu, gpu (the first of that type), an index or a name substring (see 'clpath "
                    "devices'; default $CLPATH_DEVICE, else the first GPU, else the first CPU)");
    cmd->add_option("--leaf-size", o->leaf_size, "BVH: most triangles per leaf")
        ->check(whole_number(1, 64))
        ->capture_default_str();
    cmd->add_option("--bins", o->bins, "BVH: SAH bins per axis")->check(whole_number(2, 256))->capture_default_str();
    cmd->add_option("--accel", o->accel, "Acceleration structure: bvh, or flat (one box per object, the thesis "
                    "renderer's; a baseline)")
        ->check(CLI::IsMember(accel_names()))
        ->capture_default_str();
    cmd->add_flag("--no-partial", o->no_partial,
                  "On Ctrl-C or SIGTERM write nothing (default: write the image of the samples so far; the summary "
                  "line then says interrupted=1, and the exit status is 128 + the signal's number)");
    cmd->add_flag("--quiet,-q", o->quiet, "Print only the summary line");
    return [o] { return run_render(*o); };
}

}  // namespace clpath
