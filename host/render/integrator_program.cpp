#include "render/integrator_program.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "cl/embedded_sources.hpp"
#include "render/kernel_programs.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

constexpr std::uint32_t kTile = CLP_TILE;  // one definition: kernels/shared_structs.h
constexpr std::size_t kWorkGroup = 64;

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
    params_ = ctx.buffer(sizeof(FrameParams), CL_MEM_READ_ONLY, "frame parameters");
    counters_ = ctx.buffer(sizeof(Counters), CL_MEM_READ_WRITE, "counters");
    compile();
}

void IntegratorProgram::compile() {
    const ProgramSpec spec = integrator_program(features_, kernel_shape(ctx_.device()));
    BuildResult built = build_program(ctx_, variant_source(spec.roots, variant_), variant_options(spec.options, variant_));
    render_ = Kernel();
    resolve_ = Kernel();
    add_exact_ = Kernel();
    program_ = std::move(built.program);
    compile_seconds_ = built.seconds;
    from_cache_ = built.from_cache;
    render_ = ctx_.kernel(program_.get(), "render_paths");
    resolve_ = ctx_.kernel(program_.get(), "film_resolve");
    add_exact_ = ctx_.kernel(program_.get(), "film_add_exact");
}

void IntegratorProgram::set_settings(const RenderSettings& settings) {
    validate_settings(settings);
    if (settings.accel != settings_.accel)
        throw Error(std::string("the acceleration structure cannot change in a running renderer (it was built as ") +
                    accel_name(settings_.accel) + "); make a new renderer for " + accel_name(settings.accel));
    settings_ = settings;
    const KernelFeatures f = kernel_features(scene_features_, settings_);
    if (!(f == features_)) {
        features_ = f;
        compile();
    }
    seconds_per_pixel_sample_ = 0;  // another integrator runs at another speed
}

void IntegratorProgram::launch_band(const DeviceScene& scene, Film& film, const CameraData& camera,
                                    std::uint32_t first_pixel, std::uint32_t pixel_count, std::uint32_t samples) {
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
    scene.bind(render_, 0);
    render_.arg(DeviceScene::kArgCount, params_)
        .arg(DeviceScene::kArgCount + 1, film.accumulation_buffer())
        .arg(DeviceScene::kArgCount + 2, counters_);
    p.kernel = ctx_.launch(render_, pixel_count, kWorkGroup, true);
    p.counters_read = ctx_.read_async(counters_, &p.counters, sizeof p.counters, true);
}

void IntegratorProgram::harvest(PendingLaunch& p) {
    if (!p.counters_read) return;
    const cl_int rc = clWaitForEvents(1, &p.counters_read);
    clReleaseEvent(p.counters_read);
    p.counters_read = nullptr;
    const double dt = event_seconds(p.kernel);  // releases it
    p.kernel = nullptr;
    cl_check(rc, "waiting for a render launch");
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
    while (n > 0) {
        const double target = settings_.target_launch_seconds;
        std::uint32_t samples = 1, band = all;
        if (seconds_per_pixel_sample_ <= 0) {
            band = std::min<std::uint32_t>(all, 16384);  // first launch: small, to measure
        } else {
            const double per_frame = seconds_per_pixel_sample_ * all;
            if (per_frame > target) {
                band = std::uint32_t(std::clamp(target / seconds_per_pixel_sample_, double(kWorkGroup), double(all)));
                band = std::max<std::uint32_t>(kWorkGroup, band / kWorkGroup * kWorkGroup);
            } else {
                samples = std::uint32_t(std::clamp(target / per_frame, 1.0, double(n)));
            }
        }
        samples = std::uint32_t(std::min<double>(samples, std::max(1.0, max_work / all)));
        if (double(band) * samples > max_work)
            band = std::max<std::uint32_t>(kWorkGroup, std::uint32_t(max_work / samples) / kWorkGroup * kWorkGroup);
        for (std::uint32_t first = 0; first < all; first += band) {
            launch_band(scene, film, cam, first, std::min(band, all - first), samples);
            if (seconds_per_pixel_sample_ <= 0) drain();  // the first launch measures the next ones' size
        }
        film.count_samples(samples);
        n -= samples;
    }
    drain();
    stats_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace clpath
