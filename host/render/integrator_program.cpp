#include "render/integrator_program.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "cl/embedded_sources.hpp"
#include "cl/errors.hpp"
#include "render/kernel_programs.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

constexpr std::uint32_t kTile = CLP_TILE;  // one definition: kernels/shared_structs.h
constexpr std::size_t kWorkGroup = 64;
// The wavefront's paths in flight at most (its state is about 170 bytes a path).
constexpr std::uint32_t kWavefrontPaths = 1u << 20;
// Rows of float4 per path and per shadow ray (kernels/wavefront.cl).
constexpr std::size_t kPathRows = 8, kShadowRows = 4;

// The work-items of a film: whole tiles, so the last row and column of tiles are padded.
std::uint32_t tiled_pixel_count(const Film& film) {
    const std::uint32_t tx = (std::uint32_t(film.width()) + kTile - 1) / kTile;
    const std::uint32_t ty = (std::uint32_t(film.height()) + kTile - 1) / kTile;
    return tx * ty * kTile * kTile;
}

}  // namespace

IntegratorProgram::IntegratorProgram(Context& ctx, const SceneSummary& scene, const RenderSettings& settings,
                                     KernelVariant variant)
    : ctx_(ctx), scene_features_(scene.features), settings_(settings), variant_(std::move(variant)) {
    validate_settings(settings);
    if (settings.accel != scene.accel)
        throw Error(std::string("internal: scene '") + scene.name + "' was prepared with the " +
                    accel_name(scene.accel) + " structure, the settings ask for " + accel_name(settings.accel));
    features_ = kernel_features(scene_features_, settings_);
    shape_ = resolve_kernel_shape(settings_, ctx.device().is_gpu);
    params_ = ctx.buffer(sizeof(FrameParams), CL_MEM_READ_ONLY, "frame parameters");
    counters_ = ctx.buffer(sizeof(Counters), CL_MEM_READ_WRITE, "counters");
    compile();
}

void IntegratorProgram::compile() {
    const bool wavefront = shape_ == KernelShape::Wavefront;
    const KernelCode code = kernel_code(ctx_.device());
    const ProgramSpec spec = wavefront ? wavefront_program(features_, code) : integrator_program(features_, code);
    BuildResult built = build_program(ctx_, variant_source(spec.roots, variant_), variant_options(spec.options, variant_));
    wf_ = WavefrontKernels{};
    render_ = Kernel();
    resolve_ = Kernel();
    add_exact_ = Kernel();
    program_ = std::move(built.program);
    compile_seconds_ = built.seconds;
    from_cache_ = built.from_cache;
    if (wavefront) {
        wf_.camera = ctx_.kernel(program_.get(), "wf_camera");
        wf_.trace = ctx_.kernel(program_.get(), "wf_trace");
        wf_.shade = ctx_.kernel(program_.get(), "wf_shade");
        wf_.light = ctx_.kernel(program_.get(), "wf_light");
        wf_.connect = ctx_.kernel(program_.get(), "wf_connect");
        wf_.scatter = ctx_.kernel(program_.get(), "wf_scatter");
        wf_.shadow = ctx_.kernel(program_.get(), "wf_shadow");
        wf_.next_bounce = ctx_.kernel(program_.get(), "wf_next_bounce");
        wf_.accumulate = ctx_.kernel(program_.get(), "wf_accumulate");
    } else {
        render_ = ctx_.kernel(program_.get(), "render_paths");
    }
    resolve_ = ctx_.kernel(program_.get(), "film_resolve");
    add_exact_ = ctx_.kernel(program_.get(), "film_add_exact");
    add_exact_half_ = Kernel();
    // The mask is the kernels' last parameter; kernels from before adaptive
    // sampling (a render-ab variant) have none and render every pixel.
    cl_uint args = 0;
    cl_check(clGetKernelInfo((wavefront ? wf_.camera : render_).get(), CL_KERNEL_NUM_ARGS, sizeof args, &args, nullptr),
             "clGetKernelInfo(CL_KERNEL_NUM_ARGS)");
    kernels_take_mask_ = args == (wavefront ? 8u : DeviceScene::kArgCount + 4u);
    if (adaptive_ && !kernels_take_mask_) throw Error("these kernels have no adaptive sampling");
}

Kernel& IntegratorProgram::add_exact_half_kernel() {
    if (!add_exact_half_.get()) add_exact_half_ = ctx_.kernel(program_.get(), "film_add_exact_half");
    return add_exact_half_;
}

void IntegratorProgram::set_active_pixels(const std::vector<std::uint8_t>* mask, std::uint32_t pixels) {
    drain();  // a launch in flight reads the mask it was given
    if (!mask) {
        adaptive_ = false;
        return;
    }
    if (!kernels_take_mask_) throw Error("these kernels have no adaptive sampling");
    if (mask->size() != pixels) throw Error("internal: an active-pixel mask of another size than the film");
    if (!active_.get() || active_.bytes() != mask->size())
        active_ = ctx_.buffer(mask->size(), CL_MEM_READ_ONLY, "active pixels");
    ctx_.write(active_, mask->data(), mask->size());
    adaptive_ = true;
}

void IntegratorProgram::bind_mask(Kernel& k, cl_uint index) {
    if (!kernels_take_mask_) return;
    // Without a mask the kernels never read it; any buffer satisfies the parameter.
    k.arg(index, adaptive_ ? active_ : counters_);
}

void IntegratorProgram::set_settings(const RenderSettings& settings) {
    validate_settings(settings);
    if (settings.accel != settings_.accel)
        throw Error(std::string("the acceleration structure cannot change in a running renderer (it was built as ") +
                    accel_name(settings_.accel) + "); make a new renderer for " + accel_name(settings.accel));
    settings_ = settings;
    const KernelFeatures f = kernel_features(scene_features_, settings_);
    const KernelShape shape = resolve_kernel_shape(settings_, ctx_.device().is_gpu);
    if (!(f == features_) || shape != shape_) {
        features_ = f;
        shape_ = shape;
        compile();
    }
    seconds_per_pixel_sample_ = 0;  // another integrator runs at another speed
}

FrameParams IntegratorProgram::frame_params(const DeviceScene& scene, const Film& film, const CameraData& camera,
                                            std::uint32_t first_pixel, std::uint32_t pixel_count,
                                            std::uint32_t samples) const {
    const SceneSummary& sc = scene.summary();
    FrameParams fp{};
    fp.camera = camera;
    fp.seed = settings_.seed;
    fp.first_sample = std::uint32_t(film.samples_per_pixel());
    fp.samples = samples;
    fp.rr_rule = settings_.rr_rule;
    fp.rr_min_depth = settings_.rr_min_depth;
    fp.pixel_offset = first_pixel;
    fp.pixel_count = pixel_count;
    fp.light_count = settings_.integrator == CLP_INTEGRATOR_PATH ? std::uint32_t(sc.light_count) : 0u;
    fp.env_light = sc.environment_light;
    fp.ao_distance = settings_.ao_distance > 0 ? settings_.ao_distance : 0.1f * sc.diagonal;
    fp.depth_scale = sc.diagonal;
    fp.env_color[0] = sc.environment_color.x;
    fp.env_color[1] = sc.environment_color.y;
    fp.env_color[2] = sc.environment_color.z;
    fp.env_width = std::uint32_t(sc.environment_width);
    fp.env_height = std::uint32_t(sc.environment_height);
    fp.env_scale = sc.environment_scale;
    fp.env_rot_cos = std::cos(sc.environment_rotation);
    fp.env_rot_sin = std::sin(sc.environment_rotation);
    fp.scene_flags = (sc.features.normals ? CLP_SCENE_NORMALS : 0u) | sc.surface_flags;
    fp.attr_stride = sc.attr_stride;
    if (features_.alpha && (fp.scene_flags & CLP_SCENE_ATTRIBUTES) != features_.alpha_attributes)
        throw Error("internal: the program's alpha test reads attributes " + std::to_string(features_.alpha_attributes) +
                    ", the scene has " + std::to_string(fp.scene_flags & CLP_SCENE_ATTRIBUTES));
    fp.adaptive = adaptive_ ? 1u : 0u;
    if (features_.light_bvh) {
        const LightBvhSummary& lb = sc.light_bvh;
        if (!lb.built)
            throw Error("scene '" + sc.name + "' was prepared without its light BVH (lights picked by power); "
                        "prepare it again to pick lights by the light BVH");
        for (int a = 0; a < 3; ++a) {
            fp.lbvh_origin[a] = lb.origin[a];
            fp.lbvh_scale[a] = lb.scale[a];
        }
        fp.lbvh_node_count = lb.node_count;
        fp.lbvh_infinite_count = lb.infinite_count;
    }
    return fp;
}

void IntegratorProgram::launch_band(const DeviceScene& scene, Film& film, const CameraData& camera,
                                    std::uint32_t first_pixel, std::uint32_t pixel_count, std::uint32_t samples) {
    const FrameParams fp = frame_params(scene, film, camera, first_pixel, pixel_count, samples);
    // Enqueued without waiting: the parameters are read from this slot's
    // copy, the counters land in it; the slot is harvested when it comes
    // round again or when add_samples ends, so the device always has the
    // next launch queued.
    PendingLaunch& p = pending_[next_slot_];
    next_slot_ = (next_slot_ + 1) % pending_.size();
    harvest(p);
    p.params = fp;
    p.work = double(pixel_count) * samples;
    ctx_.write_async(params_, &p.params, sizeof p.params);
    ctx_.fill_async(counters_, 0);
    if (shape_ == KernelShape::Wavefront) {
        launch_waves(scene, film, p, pixel_count, samples);
    } else {
        scene.bind(render_, 0);
        render_.arg(DeviceScene::kArgCount, params_)
            .arg(DeviceScene::kArgCount + 1, film.accumulation_buffer())
            .arg(DeviceScene::kArgCount + 2, counters_);
        bind_mask(render_, DeviceScene::kArgCount + 3);
        p.first_kernel = ctx_.launch(render_, pixel_count, kWorkGroup, true);
    }
    p.counters_read = ctx_.read_async(counters_, &p.counters, sizeof p.counters, true);
}

void IntegratorProgram::ensure_wavefront_buffers(std::uint32_t paths) {
    if (paths <= wf_.capacity) return;
    const std::size_t n = paths;
    // A hit is one float4 row; an instanced scene's adds the instance, an int per path after the rows (wf_trace).
    const std::size_t hit_bytes = features_.instances ? 20 : 16;
    ctx_.check_fits({{"wavefront path state", n * kPathRows * 16},
                     {"wavefront hits", n * hit_bytes},
                     {"wavefront shadow rays", n * kShadowRows * 16},
                     {"wavefront queues", 3 * n * sizeof(cl_uint)}});
    wf_.paths = ctx_.buffer(n * kPathRows * 16, CL_MEM_READ_WRITE, "wavefront path state");
    wf_.hits = ctx_.buffer(n * hit_bytes, CL_MEM_READ_WRITE, "wavefront hits");
    wf_.shadows = ctx_.buffer(n * kShadowRows * 16, CL_MEM_READ_WRITE, "wavefront shadow rays");
    wf_.queues[0] = ctx_.buffer(n * sizeof(cl_uint), CL_MEM_READ_WRITE, "wavefront queue");
    wf_.queues[1] = ctx_.buffer(n * sizeof(cl_uint), CL_MEM_READ_WRITE, "wavefront queue");
    wf_.scatter_queue = ctx_.buffer(n * sizeof(cl_uint), CL_MEM_READ_WRITE, "wavefront scatter queue");
    wf_.counts = ctx_.buffer(CLP_WF_COUNT_SLOTS * sizeof(cl_uint), CL_MEM_READ_WRITE, "wavefront queue lengths");
    wf_.capacity = paths;
}

void IntegratorProgram::launch_waves(const DeviceScene& scene, Film& film, PendingLaunch& p,
                                     std::uint32_t pixel_count, std::uint32_t samples) {
    // As many samples a wave as the path state holds: each launch then has
    // more paths to run and a launch's fixed cost is paid fewer times.
    const std::uint32_t per_wave = std::max<std::uint32_t>(1, std::min(samples, kWavefrontPaths / pixel_count));
    ensure_wavefront_buffers(pixel_count * per_wave);
    const cl_uint cap = wf_.capacity;
    // On a CPU the queue lengths are read back after each bounce to size the
    // next launches (a read costs microseconds there, an idle work-item
    // does not); a GPU runs every bounce over the whole wave, the work-items
    // past the queue's end returning at once, and never waits for the host.
    const bool read_lengths = !ctx_.device().is_gpu;
    scene.bind(wf_.trace, 0);
    scene.bind(wf_.shade, 0);
    scene.bind(wf_.light, 0);
    scene.bind(wf_.connect, 0);
    scene.bind(wf_.scatter, 0);
    scene.bind(wf_.shadow, 0);
    const cl_uint k = DeviceScene::kArgCount;
    wf_.camera.arg(0, params_).arg(3, wf_.paths).arg(4, cap).arg(6, wf_.counts);
    wf_.trace.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 4, wf_.counts).arg(k + 5, wf_.hits)
        .arg(k + 6, counters_);
    wf_.shade.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 4, wf_.scatter_queue)
        .arg(k + 5, wf_.counts).arg(k + 6, wf_.hits);
    wf_.light.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 3, wf_.scatter_queue)
        .arg(k + 4, wf_.counts);
    wf_.connect.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 3, wf_.scatter_queue)
        .arg(k + 4, wf_.counts).arg(k + 5, wf_.hits).arg(k + 6, wf_.shadows);
    wf_.scatter.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 3, wf_.scatter_queue)
        .arg(k + 5, wf_.counts).arg(k + 6, wf_.hits);
    // Next-event estimation (light samples, shadow rays): only the integrator that has it.
    const bool sample_lights = settings_.integrator == CLP_INTEGRATOR_PATH;
    wf_.shadow.arg(k, params_).arg(k + 1, wf_.paths).arg(k + 2, cap).arg(k + 3, wf_.counts).arg(k + 4, wf_.shadows)
        .arg(k + 5, counters_);
    wf_.next_bounce.arg(0, wf_.counts);
    wf_.accumulate.arg(0, params_).arg(2, wf_.paths).arg(3, cap).arg(4, film.accumulation_buffer()).arg(5, counters_);
    bind_mask(wf_.camera, 7);
    bind_mask(wf_.accumulate, 6);
    for (cl_uint first = 0; first < samples; first += per_wave) {
        const cl_uint n = std::min(per_wave, samples - first);
        const std::size_t paths = std::size_t(pixel_count) * n;
        ctx_.fill_async(wf_.counts, 0);
        wf_.camera.arg(1, first).arg(2, n).arg(5, wf_.queues[0]);
        cl_event e = ctx_.launch(wf_.camera, paths, kWorkGroup, first == 0);
        if (first == 0) p.first_kernel = e;
        // Bounce d traces the rays of the paths still alive after d bounces:
        // at most CLP_MAX_DEPTH + 1 closest hits a path.
        for (std::uint32_t d = 0, in = 0; d <= settings_.max_depth; ++d, in ^= 1u) {
            std::size_t global = paths;
            if (read_lengths) {
                cl_uint queued = 0;
                ctx_.read(wf_.counts, &queued, sizeof queued);
                if (queued == 0) break;
                global = queued;
            }
            wf_.trace.arg(k + 3, wf_.queues[in]);
            wf_.shade.arg(k + 3, wf_.queues[in]);
            wf_.scatter.arg(k + 4, wf_.queues[in ^ 1u]);
            // The paths that scatter are at most those shaded: the same
            // launch size, the work-items past the scatter queue's end idle.
            ctx_.launch(wf_.trace, global, kWorkGroup);
            ctx_.launch(wf_.shade, global, kWorkGroup);
            if (sample_lights) {
                ctx_.launch(wf_.light, global, kWorkGroup);
                ctx_.launch(wf_.connect, global, kWorkGroup);
            }
            ctx_.launch(wf_.scatter, global, kWorkGroup);
            ctx_.launch(wf_.shadow, global, kWorkGroup);
            ctx_.launch(wf_.next_bounce, 1, 0);
        }
        wf_.accumulate.arg(1, n);
        if (kernels_take_mask_) wf_.accumulate.arg(7, first);
        ctx_.launch(wf_.accumulate, pixel_count, kWorkGroup);
    }
}

void IntegratorProgram::harvest(PendingLaunch& p) {
    if (!p.counters_read) return;
    // From the launch's first kernel to its counters: its time on the device.
    const double dt = event_span_seconds(std::exchange(p.first_kernel, nullptr), std::exchange(p.counters_read, nullptr));
    stats_.rays += p.counters.rays;
    stats_.nonfinite += p.counters.nonfinite;
    ++stats_.launches;
    // Smoothed, so one slow launch does not swing the next one's size.
    const double s = dt / p.work;
    seconds_per_pixel_sample_ = seconds_per_pixel_sample_ > 0 ? 0.5 * (seconds_per_pixel_sample_ + s) : s;
}

void IntegratorProgram::drain() {
    for (std::size_t k = 0; k < pending_.size(); ++k) harvest(pending_[(next_slot_ + k) % pending_.size()]);
}

IntegratorProgram::~IntegratorProgram() {
    try {
        drain();
    } catch (...) {
        // A failed device: its events are released as far as they can be.
    }
}

void IntegratorProgram::add_samples(const DeviceScene& scene, Film& film, const Camera& camera, std::uint32_t n) {
    if (&scene.context() != &ctx_ || &film.context() != &ctx_)
        throw Error("internal: the scene, film and program must be on one device");
    if (camera.width != film.width() || camera.height != film.height())
        throw Error("internal: the camera's resolution is not the film's");
    if (film.samples_per_pixel() + n > kMaxSamplesPerPixel)
        throw Error("at most " + std::to_string(kMaxSamplesPerPixel) + " samples per pixel can be accumulated");
    const CameraData cam = camera_data(camera);
    const std::uint32_t all = tiled_pixel_count(film);
    // Each launch's ray counter is 32-bit: keep pixels * samples * rays per
    // sample below 2^32, by fewer samples per launch and, where one sample of
    // every pixel is already too much (a 16384^2 film at depth 1024), by bands.
    const double max_work = double(0xffffffffu) / double(max_rays_per_sample(settings_));
    const auto t0 = std::chrono::steady_clock::now();
    // Pixels per launch of one sample each that take about the target time
    // (all of them where a whole frame takes less), from the measured speed.
    auto one_sample_band = [&](double target) {
        if (seconds_per_pixel_sample_ * all <= target) return all;
        const auto b = std::uint32_t(std::clamp(target / seconds_per_pixel_sample_, double(kWorkGroup), double(all)));
        return std::max<std::uint32_t>(kWorkGroup, b / kWorkGroup * kWorkGroup);
    };
    // What every band obeys: the wavefront's path state, the 32-bit ray counter.
    auto capped = [&](std::uint32_t band, std::uint32_t samples) {
        if (shape_ == KernelShape::Wavefront && band > kWavefrontPaths) band = kWavefrontPaths;
        if (double(band) * samples > max_work)
            band = std::max<std::uint32_t>(kWorkGroup, std::uint32_t(max_work / samples) / kWorkGroup * kWorkGroup);
        return band;
    };
    while (n > 0) {
        const double target = settings_.target_launch_seconds;
        std::uint32_t samples = 1, band = all;
        const bool measuring = seconds_per_pixel_sample_ <= 0;
        if (measuring) {
            band = std::min<std::uint32_t>(all, 16384);  // first launch: small, to measure
        } else if (seconds_per_pixel_sample_ * all > target) {
            band = one_sample_band(target);
        } else {
            samples = std::uint32_t(std::clamp(target / (seconds_per_pixel_sample_ * all), 1.0, double(n)));
        }
        samples = std::uint32_t(std::min<double>(samples, std::max(1.0, max_work / all)));
        band = capped(band, samples);
        for (std::uint32_t first = 0; first < all;) {
            const std::uint32_t count = std::min(band, all - first);
            launch_band(scene, film, cam, first, count, samples);
            first += count;
            if (measuring && seconds_per_pixel_sample_ <= 0) {
                // The first launch sizes the rest of this pass's launches:
                // the pass does not go on in launches of the measuring size
                // (16 of them over 512x512), small enough to run slower.
                drain();
                band = capped(one_sample_band(target), samples);
            }
        }
        film.count_samples(samples);
        n -= samples;
    }
    drain();
    stats_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace clpath
