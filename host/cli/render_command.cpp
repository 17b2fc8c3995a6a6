#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bvh/bvh.hpp"
#include "cl/context.hpp"
#include "cli/checkpoint_options.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/scene_overrides.hpp"
#include "image/tone_map.hpp"
#include "cli/interrupt.hpp"
#include "cli/progress.hpp"
#include "image/image.hpp"
#include "cl/device_set.hpp"
#include "denoise/denoiser.hpp"
#include "denoise/guides.hpp"
#include "mpi/launch.hpp"
#include "render/checkpoint.hpp"
#include "render/render_session.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/load/gltf_model.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/env_values.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// The kernel shapes the devices ran, "mega", or "mega,wavefront" where they differ.
std::string kernel_shapes_used(const std::vector<DeviceShare>& shares) {
    std::string used;
    for (const DeviceShare& s : shares) {
        const std::string name = kernel_shape_name(s.kernel_shape);
        if (("," + used + ",").find("," + name + ",") == std::string::npos) used += (used.empty() ? "" : ",") + name;
    }
    return used;
}

// The longest gap between progress lines in a log, in milliseconds. Meant for
// tests that cannot wait 10 s; documented in README.
double progress_interval_from_env() {
    const auto ms = env_whole_number("CLPATH_PROGRESS_INTERVAL_MS", 10, 86400000, "milliseconds");
    return ms ? double(*ms) / 1000.0 : kDefaultProgressInterval;
}

// Options left unset (nullopt) take the scene file's value, then the default.
struct RenderOptions {
    std::string scene = "cornell";
    std::string gltf_camera;  // a glTF file's camera, by name or index
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
    std::string kernel = "auto";
    std::optional<std::string> light_sampler;
    std::uint32_t chunk_samples = 0;
    double checkpoint_seconds = 0;
    std::string checkpoint_file, resume;
    bool keep_checkpoint = false;
    float exposure = 0;
    std::string tonemap = "clamp";
    std::optional<std::string> camera, env;
    bool no_ground = false;
    bool no_partial = false;
    bool denoise = false;
    std::optional<double> noise_target;
    std::vector<std::string> sample_count_images;
};

// Each pixel's sample count as an image: the count itself in EXR and PFM, in
// PNG grey from black (none) to white (the most any pixel took).
RenderedImage sample_count_image(const ExactFilm& film) {
    RenderedImage out;
    out.linear.width = film.width();
    out.linear.height = film.height();
    const std::size_t pixels = std::size_t(film.width()) * std::size_t(film.height());
    out.linear.rgb.resize(pixels * 3);
    std::uint64_t most = 1;
    for (std::size_t p = 0; p < pixels; ++p) most = std::max(most, film.samples_of(p));
    out.srgb8.resize(pixels * 4);
    for (std::size_t p = 0; p < pixels; ++p) {
        const std::uint64_t n = film.samples_of(p);
        for (int c = 0; c < 3; ++c) out.linear.rgb[p * 3 + c] = float(n);
        const auto grey = std::uint8_t(std::lround(255.0 * double(n) / double(most)));
        out.srgb8[p * 4] = out.srgb8[p * 4 + 1] = out.srgb8[p * 4 + 2] = grey;
        out.srgb8[p * 4 + 3] = 255;
    }
    return out;
}

// Only a bare mesh (an OBJ, or a glTF model) gets the presentation's ground
// (docs/scene-format.md, "Bare meshes"); scene files and built-in scenes do not.
bool is_bare_mesh(const std::string& spec) {
    std::string ext = std::filesystem::path(spec).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

// Where --denoise puts the denoised twin of an output: out.png -> out.denoised.png.
std::string denoised_path(const std::string& out) {
    std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + ".denoised" + p.extension().string())).string();
}

// --device, one device or a list. A list's faults (an empty item, 'all' among
// others, a device named twice) are bad usage (exit 2), as an unknown device is.
std::vector<DeviceInfo> choose_devices(const std::string& spec) {
    if (spec.find(',') == std::string::npos) return select_devices(spec);
    std::vector<DeviceInfo> out;
    std::size_t start = 0;
    for (std::size_t end = 0; end != std::string::npos; start = end + 1) {
        end = spec.find(',', start);
        const std::string item = spec.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (item.empty()) throw UsageError("--device '" + spec + "': an empty item in the device list");
        if (item == "all") throw UsageError("--device '" + spec + "': 'all' cannot be combined with other devices");
        DeviceInfo d = select_device(item);
        for (const auto& e : out)
            if (e.index == d.index)
                throw UsageError("--device '" + spec + "': device [" + std::to_string(d.index) + "] " + d.name +
                                 " is named twice ('" + item + "')");
        out.push_back(std::move(d));
    }
    return out;
}

int run_render(const RenderOptions& o) {
    // Everything that can be checked before rendering is checked first.
    const auto load_start = std::chrono::steady_clock::now();
    const double progress_interval = progress_interval_from_env();
    if (!o.gltf_camera.empty() && !is_gltf_file(o.scene))
        throw UsageError("--gltf-camera " + o.gltf_camera + ": " + o.scene +
                         " is not a glTF model (the option picks a camera of a .gltf or .glb file)");
    LoadOptions load;
    load.gltf_camera = o.gltf_camera;
    load.presentation.ground = !o.no_ground;
    if (o.env) load.presentation.environment = parse_env_option(*o.env);
    if (o.no_ground && !is_bare_mesh(o.scene))
        std::fprintf(stderr, "clpath: warning: --no-ground has no effect on %s: only a bare mesh gets a ground\n",
                     o.scene.c_str());
    Scene scene;
    try {
        scene = load_scene(o.scene, load);
    } catch (const UnknownGltfCamera& e) {
        throw UsageError(std::string("--gltf-camera: ") + e.what());
    }
    if (load.presentation.environment) scene.environment = *load.presentation.environment;
    if (o.camera) scene.camera = apply_camera_option(*o.camera, scene.camera);
    DisplaySettings display;
    display.exposure_stops = o.exposure;
    display.tone_map = parse_tone_map(o.tonemap);
    const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    if (!o.quiet)
        for (const auto& n : scene.notes) std::fprintf(stderr, "clpath: %s\n", n.c_str());
    if (!o.quiet)
        std::fprintf(stderr, "clpath: loaded '%s' from %s in %.3f s: %zu triangles%s, %zu materials\n",
                     scene.name.c_str(), o.scene.c_str(), load_seconds, scene.placed_triangle_count(),
                     scene.instances.empty() ? ""
                                             : (" placed by " + std::to_string(scene.instances.size()) +
                                                " instances of " + std::to_string(scene.meshes.size()) +
                                                (scene.meshes.size() == 1 ? " mesh" : " meshes"))
                                                   .c_str(),
                     scene.materials.size());
    // The scene file's render block gives the defaults; options override the settings, never the scene.
    RenderSettings settings = settings_from_scene(scene.render);
    if (o.max_depth) settings.max_depth = *o.max_depth;
    if (o.seed) settings.seed = *o.seed;
    if (o.rr) settings.rr_rule = parse_rr_rule(*o.rr);
    if (o.integrator) settings.integrator = parse_integrator(*o.integrator);
    if (o.ao_distance) settings.ao_distance = *o.ao_distance;
    settings.rr_min_depth = o.rr_min_depth;
    settings.hemisphere = parse_hemisphere(o.hemisphere);
    settings.all_features = o.all_features;
    settings.bvh.max_leaf_size = o.leaf_size;
    settings.bvh.bins = o.bins;
    settings.accel = parse_accel(o.accel);
    settings.kernel_shape = parse_kernel_shape(o.kernel);
    if (o.light_sampler) settings.light_sampler = parse_light_sampler(*o.light_sampler);
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    std::vector<std::string> outputs = o.outputs;
    if (outputs.empty()) {
        // The default destination is created; one the user names must exist.
        std::filesystem::create_directories("out");
        outputs = {"out/" + scene.name + ".png", "out/" + scene.name + ".exr"};
    }
    for (const auto& out : outputs) {
        check_output_path(out);
        if (o.denoise) check_output_path(denoised_path(out));
    }
    // The scene file's render block gives the default noise target, as it gives spp.
    const double noise_target = o.noise_target ? *o.noise_target : scene.render.noise_target;
    for (const auto& f : o.sample_count_images) check_output_path(f);
    // The library is loaded and its device made before anything renders, so
    // a missing library costs no render.
    std::unique_ptr<Denoiser> denoiser;
    if (o.denoise) {
        try {
            denoiser = std::make_unique<Denoiser>();
        } catch (const Error& e) {
            throw Error(std::string("--denoise: ") + e.what());
        }
        if (!o.quiet) std::fprintf(stderr, "clpath: denoising with %s\n", denoiser->library_path().c_str());
    }
    const std::string checkpoint_path = o.checkpoint_file.empty() ? outputs.front() + ".checkpoint" : o.checkpoint_file;
    if (o.checkpoint_seconds > 0) check_checkpoint_destination(checkpoint_path, !o.checkpoint_file.empty());
    else if (!o.checkpoint_file.empty())
        std::fprintf(stderr, "clpath: warning: --checkpoint-file has no effect without --checkpoint SECONDS\n");
    if (!o.resume.empty()) check_resume_file(o.resume);
    // --time alone renders until the time is up; --spp with it caps the samples.
    const std::uint64_t spp = o.spp ? *o.spp : (o.time_limit > 0 ? 0 : scene.render.spp);
    validate_settings(settings);
    if (!scene.has_emitter())
        std::fprintf(stderr, "clpath: warning: scene '%s' has no emitter; the image will be black\n",
                     scene.name.c_str());

    const std::vector<DeviceInfo> devices = choose_devices(o.device);
    ProcessGroup* mpi = mpi_job();
    const bool lead = !mpi || mpi_rank() == 0;
    if (!o.quiet) {
        std::string names;
        for (const auto& d : devices) names += (names.empty() ? "" : ", ") + d.describe();
        std::fprintf(stderr, "clpath: rendering '%s' (%zu triangles) at %dx%d with '%s' on %s\n", scene.name.c_str(),
                     scene.placed_triangle_count(), scene.camera.width, scene.camera.height,
                     integrator_name(settings.integrator), names.c_str());
    }
    SessionOptions so;
    so.spp = spp;
    so.time_limit = o.time_limit;
    so.chunk_samples = o.chunk_samples;
    so.checkpoint_seconds = o.checkpoint_seconds;
    so.checkpoint_path = checkpoint_path;
    so.resume_path = o.resume;
    so.noise_target = noise_target;
    const bool show_progress = !o.quiet && lead;
    InterruptFlag interrupt;
    // Progress keeps its own clock, started once the scene is prepared: the
    // render_session()'s starts with the first chunk, and a log should show lines
    // while the devices get ready too.
    std::unique_ptr<Progress> progress;
    SessionHooks hooks;
    hooks.on_resumed = [&](std::uint64_t spp) {
        if (lead && !o.quiet)
            std::fprintf(stderr, "clpath: resumed at %llu spp from %s\n", (unsigned long long)spp, o.resume.c_str());
    };
    hooks.on_start = [&](const BvhStats& bvh) {
        if (show_progress) std::fprintf(stderr, "clpath: %s\n", describe(bvh).c_str());
        ProgressOptions po;
        po.log_interval = progress_interval;
        progress = std::make_unique<Progress>(spp, o.time_limit, show_progress, po);
    };
    hooks.on_progress = [&](std::uint64_t done) { progress->update(done); };
    hooks.stop_requested = [&] { return interrupt.raised(); };
    SessionResult result;
    try {
        result = render_session(scene, settings, devices, so, hooks, mpi);
    } catch (const UsageError&) {
        throw;  // about the command line or the environment, not the scene
    } catch (const CheckpointError&) {
        throw;  // about the checkpoint's file, which the message names
    } catch (const Error& e) {
        throw Error(o.scene + ": " + e.what());
    }
    if (progress) progress->finish();
    GuideRender guides;
    if (denoiser && !result.stopped) {
        try {
            guides = render_guides(scene, settings, devices, kGuideSamples, mpi);
        } catch (const UsageError&) {
            throw;
        } catch (const Error& e) {
            throw Error(o.scene + ": the denoiser's guides: " + e.what());
        }
        if (show_progress)
            std::fprintf(stderr, "clpath: rendered the denoiser's guides (albedo, normals; %llu spp each) in %.3f s\n",
                         (unsigned long long)kGuideSamples, guides.seconds);
    }
    if (!result.leads) return 0;
    const std::uint64_t done_spp = result.film.samples_per_pixel();
    // Interrupted: the partial image is written, then the exit status is the
    // shell's for a death by that signal (130 for SIGINT, 143 for SIGTERM), so
    // that a script can tell an interrupted render from a finished one.
    const int stopped_status = 128 + interrupt.signal();
    if (result.stopped) {
        std::fprintf(stderr, "clpath: interrupted by signal %d after %llu samples per pixel\n", interrupt.signal(),
                     (unsigned long long)done_spp);
        if (o.no_partial) {
            std::fprintf(stderr, "clpath: --no-partial: nothing written\n");
            return stopped_status;
        }
    }
    if (done_spp == 0) throw Error("no sample was finished, so there is no image to write");
    RenderedImage image;
    image.linear = result.film.mean();
    // PNG gets the display transform (exposure, tone map); EXR and PFM keep the linear radiance.
    image.srgb8 = display_srgb8(image.linear, display);
    for (const auto& out : outputs) {
        write_image(out, image);
        if (!o.quiet) std::fprintf(stderr, "clpath: wrote %s\n", out.c_str());
    }
    for (const auto& f : o.sample_count_images) {
        write_image(f, sample_count_image(result.film));
        if (!o.quiet) std::fprintf(stderr, "clpath: wrote %s\n", f.c_str());
    }
    double denoise_seconds = 0;
    if (denoiser && result.stopped) {
        std::fprintf(stderr, "clpath: interrupted: not denoised\n");
    } else if (denoiser) {
        const auto start = std::chrono::steady_clock::now();
        RenderedImage denoised;
        denoised.linear = denoiser->denoise(image.linear, &guides.guides);
        denoise_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        denoised.srgb8 = display_srgb8(denoised.linear, display);
        if (!o.quiet)
            std::fprintf(stderr, "clpath: denoised in %.3f s (%.3f s per megapixel)\n", denoise_seconds,
                         denoise_seconds / (double(scene.camera.width) * scene.camera.height * 1e-6));
        for (const auto& out : outputs) {
            write_image(denoised_path(out), denoised);
            if (!o.quiet) std::fprintf(stderr, "clpath: wrote %s\n", denoised_path(out).c_str());
        }
    }
    // A finished render needs its checkpoints no more: the one it wrote and the one it resumed.
    if (!result.stopped && !o.keep_checkpoint)
        for (const std::string& path : {o.checkpoint_seconds > 0 ? so.checkpoint_path : std::string(), o.resume})
            if (!path.empty() && std::filesystem::remove(path) && !o.quiet)
                std::fprintf(stderr, "clpath: removed the checkpoint %s (the render finished; --keep-checkpoint keeps it)\n",
                             path.c_str());

    // Rates count this run's samples only: a resumed render's earlier ones took no time here.
    const double wall = result.wall_seconds;
    // Samples this run took (a resumed render's earlier ones took no time
    // here): each pixel's own count under adaptive sampling, less what the
    // checkpoint held (at most resumed_spp per pixel).
    const std::uint64_t run_spp = done_spp - std::min(done_spp, result.resumed_spp);
    double samples = double(run_spp) * scene.camera.width * scene.camera.height;
    std::string adaptive_summary;
    if (noise_target > 0) {
        std::uint64_t least = ~0ull, most = 0;
        double taken = 0;
        samples = 0;
        const std::size_t pixels = std::size_t(scene.camera.width) * std::size_t(scene.camera.height);
        for (std::size_t p = 0; p < pixels; ++p) {
            const std::uint64_t n = result.film.samples_of(p);
            least = std::min(least, n);
            most = std::max(most, n);
            taken += double(n);
            samples += double(n - std::min(n, result.resumed_spp));
        }
        char buf[200];
        std::snprintf(buf, sizeof buf, " noise_target=%g spp_min=%llu spp_max=%llu spp_mean=%.2f converged=%d",
                      noise_target, (unsigned long long)least, (unsigned long long)most, taken / double(pixels),
                      result.converged ? 1 : 0);
        adaptive_summary = buf;
    }
    std::string instance_summary;
    if (result.instanced) {
        const TwoLevelStats& is = result.instances;
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      " instances=%zu instanced_meshes=%zu placed_triangles=%zu tlas_bytes=%zu tlas_depth=%d "
                      "tlas_build_ms=%.2f blas_bytes=%zu blas_build_ms=%.2f",
                      is.instances, is.meshes, is.placed_triangles, is.top_bytes, is.top_depth, is.top_build_ms,
                      is.bottom_bytes, is.bottom_build_ms);
        instance_summary = buf;
    }
    // The light sampler that ran, and the light BVH it walked: the scene was
    // prepared with the tree exactly where the path integrator picks by it.
    std::string light_summary;
    if (settings.integrator == CLP_INTEGRATOR_PATH && result.light_bvh.built) {
        char buf[160];
        std::snprintf(buf, sizeof buf, " light_sampler=bvh light_bvh_nodes=%u light_bvh_depth=%d light_bvh_build_ms=%.2f",
                      result.light_bvh.node_count, result.light_bvh.depth, result.light_bvh.build_ms);
        light_summary = buf;
    } else if (settings.integrator == CLP_INTEGRATOR_PATH) {
        light_summary = " light_sampler=power";
    }
    std::string device_names;
    for (const auto& d : devices) device_names += (device_names.empty() ? "" : ", ") + d.name;
    std::printf(
        "summary: device=\"%s\" devices=%zu integrator=%s triangles=%zu bvh_build_ms=%.2f bvh_nodes=%zu bvh_sah=%.2f "
        "spp=%llu render_s=%.3f msamples_per_s=%.3f mrays_per_s=%.3f rays=%llu nonfinite=%llu accel=%s kernel=%s "
        "bytes_to_device=%llu bytes_from_device=%llu scene_device_bytes=%zu%s%s%s%s%s%s\n",
        device_names.c_str(), result.shares.size(), integrator_name(settings.integrator), scene.placed_triangle_count(),
        result.bvh.build_ms, result.bvh.node_count, result.bvh.sah_cost, (unsigned long long)done_spp, wall,
        samples / wall * 1e-6, double(result.rays) / wall * 1e-6, (unsigned long long)result.rays,
        (unsigned long long)result.nonfinite, accel_name(settings.accel), kernel_shapes_used(result.shares).c_str(),
        (unsigned long long)result.bytes_to_device, (unsigned long long)result.bytes_from_device,
        result.scene_device_bytes, light_summary.c_str(), instance_summary.c_str(), result.resumed_spp ? (" resumed_spp=" + std::to_string(result.resumed_spp)).c_str() : "",
        adaptive_summary.c_str(), result.stopped ? " interrupted=1" : "",
        denoiser && !result.stopped
            ? (" denoise_s=" + std::to_string(denoise_seconds) + " guides_s=" + std::to_string(guides.seconds)).c_str()
            : "");
    if (result.shares.size() > 1 || mpi)
        for (const auto& s : result.shares)  // a device's share: its chunks of this run
            std::printf("device: \"%s\" chunks=%llu spp=%llu share=%.1f%% msamples_per_s=%.3f\n", s.device.c_str(),
                        (unsigned long long)s.chunks, (unsigned long long)s.samples_per_pixel,
                        done_spp ? 100.0 * double(s.samples_per_pixel) / double(done_spp) : 0.0,
                        s.busy_seconds > 0 ? double(s.samples_per_pixel) * scene.camera.width * scene.camera.height /
                                                 s.busy_seconds * 1e-6
                                           : 0.0);
    if (result.nonfinite)
        std::fprintf(stderr, "clpath: warning: %llu samples were NaN or infinite and were dropped\n",
                     (unsigned long long)result.nonfinite);
    return result.stopped ? stopped_status : 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene progressively and write the image");
    cmd->add_option("scene", o->scene, scene_argument_help())
        ->capture_default_str();
    cmd->add_option("--gltf-camera", o->gltf_camera, "A glTF model's camera, by name or index (default: the first)")
        ->check(non_empty("a camera's name or index"));
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
    cmd->add_option("--exposure", o->exposure, "PNG only: brighten by this many stops (radiance x 2^stops)")
        ->check(real_number(-20, 20))
        ->capture_default_str();
    cmd->add_option("--tonemap", o->tonemap,
                    "PNG only: clamp (clip at white), reinhard (L/(1+L) on luminance) or aces (Narkowicz's "
                    "fitted ACES filmic curve); EXR and PFM stay linear")
        ->check(CLI::IsMember(tone_map_names()))
        ->capture_default_str();
    cmd->add_option("--camera", o->camera,
                    "Camera override, any of 'from=X,Y,Z;to=X,Y,Z;fov=DEGREES;up=X,Y,Z;aperture=R;focus=D' "
                    "(aperture: thin-lens radius, 0 a pinhole; focus: distance of the sharp plane, default the "
                    "target's; quote it: ';' is a shell separator)");
    cmd->add_option("--env", o->env,
                    "Environment override: a colour R,G,B (or one grey value) or an equirectangular image "
                    "(.exr, .hdr or any format OpenImageIO reads); for a bare mesh (.obj, .gltf, .glb) it replaces "
                    "the default sky and sun");
    cmd->add_flag("--denoise", o->denoise,
                  "Also write each output denoised by Intel Open Image Denoise, beside it (out.png: "
                  "out.denoised.png), guided by albedo and normals passes; the estimate is unchanged");
    cmd->add_option("--noise-target", o->noise_target,
                    "Adaptive sampling: a pixel stops taking samples once its estimated error, |mean of all samples "
                    "- mean of the odd ones| / sqrt(mean), is below this (Cycles' noise threshold, e.g. 0.01); the "
                    "render ends when every pixel has, or at --spp or --time (default: the scene's, else off)")
        ->check(real_number(0, 1, true));
    cmd->add_option("--sample-count-image", o->sample_count_images,
                    "Also write each pixel's sample count: .exr or .pfm (the count), .png (grey, white the most); "
                    "repeatable");
    cmd->add_flag("--no-ground", o->no_ground, "A bare mesh (.obj, .gltf, .glb) gets no ground plane");
    cmd->add_option("--out,-o", o->outputs,
                    "Output image, .png (8-bit sRGB), .exr or .pfm (linear float); repeatable "
                    "(default: out/SCENE.png and out/SCENE.exr)");
    cmd->add_option("--device,-d", o->device,
                    "OpenCL device(s): an index or name substring (see 'clpath devices'), a comma-separated list "
                    "of them, or 'all'; cpu or gpu picks the first device of that type")
        ->check(non_empty(kDeviceChoices));
    cmd->add_option("--chunk", o->chunk_samples,
                    "Samples per chunk handed to a device (default: spp/64, 1 to 64; 4 with --time alone)")
        ->check(whole_number(1, 1u << 20));
    cmd->add_option("--checkpoint", o->checkpoint_seconds, "Save the running sums every this many seconds")
        ->check(real_number(0.001, 1e9));
    cmd->add_option("--checkpoint-file", o->checkpoint_file,
                    "Where checkpoints go (default: the first output + .checkpoint); its folder must exist");
    cmd->add_option("--resume", o->resume, "Continue the render saved in this checkpoint (same scene, --spp, --chunk, --noise-target)");
    cmd->add_flag("--keep-checkpoint", o->keep_checkpoint,
                  "Keep the checkpoint (written, or resumed) after the render finishes (default: it is removed)");
    cmd->add_flag("--no-partial", o->no_partial,
                  "On Ctrl-C or SIGTERM, write nothing (default: the samples so far); either way the exit status "
                  "is 130 (SIGINT) or 143 (SIGTERM)");
    cmd->add_option("--leaf-size", o->leaf_size, "BVH: most triangles per leaf")
        ->check(whole_number(1, 64))
        ->capture_default_str();
    cmd->add_option("--bins", o->bins, "BVH: SAH bins per axis")->check(whole_number(2, 256))->capture_default_str();
    cmd->add_option("--accel", o->accel, "Acceleration structure: bvh, or flat (one box per object, the thesis "
                    "renderer's; a baseline)")
        ->check(CLI::IsMember(accel_names()))
        ->capture_default_str();
    cmd->add_option("--light-sampler", o->light_sampler,
                    "Next-event estimation's pick of a light: power (alias table), bvh (the light BVH: by each "
                    "light's estimated contribution at the point), auto (bvh for 16 or more finite lights "
                    "spread over the scene, else power; default: the scene file's, else auto)")
        ->check(CLI::IsMember(light_sampler_names()));
    cmd->add_option("--kernel", o->kernel,
                    "Kernel shape: auto (the one measured faster on the device's kind: mega today), mega (one kernel per path) "
                    "or wavefront (small kernels over queues of paths; path and path-bsdf only)")
        ->check(CLI::IsMember(kernel_shape_names()))
        ->capture_default_str();
    cmd->add_flag("--quiet,-q", o->quiet, "Print only the summary line");
    return [o] { return run_render(*o); };
}

}  // namespace clpath
