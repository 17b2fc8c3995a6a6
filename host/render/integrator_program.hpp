#pragma once
// The integrator as a compiled OpenCL program: the kernels specialised to the
// features a scene and settings need (kernel_features.hpp), built or loaded
// through the binary cache, and the launches that add samples to a film,
// sized to a time target and to the kernels' 32-bit counters.
#include <array>
#include <cstdint>
#include <vector>

#include "cl/context.hpp"
#include "cl/embedded_sources.hpp"
#include "cl/program.hpp"
#include "render/device_scene.hpp"
#include "render/film.hpp"
#include "render/kernel_features.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

// What the launches did since the last reset_stats().
struct LaunchStats {
    std::uint64_t rays = 0;       // every ray traced
    std::uint64_t nonfinite = 0;  // samples dropped as NaN/inf
    std::uint64_t launches = 0;
    double render_seconds = 0;    // wall time spent in add_samples, to the launches' completion
};

// Most rays one sample can trace, for any integrator: a path traces its
// camera ray and one ray per bounce (max_depth + 1; one fewer in a program
// with no emission or environment, kernels/path.cl path_next_ray_gathers)
// and one shadow ray per bounce (max_depth); ambient occlusion 2. Launches
// are sized so that the kernels' 32-bit ray counter cannot overflow (host
// totals are 64-bit).
constexpr std::uint64_t max_rays_per_sample(const RenderSettings& s) { return 2ull * s.max_depth + 2; }

class IntegratorProgram {
public:
    // Compiles (or loads from the cache) the kernels for this scene under these
    // settings, whose acceleration structure must be the scene's. Throws
    // clpath::Error for invalid settings or a failed build.
    // A variant (bench render-ab) replaces kernel files and adds build options.
    IntegratorProgram(Context& ctx, const SceneSummary& scene, const RenderSettings& settings,
                      KernelVariant variant = {});
    ~IntegratorProgram();
    IntegratorProgram(const IntegratorProgram&) = delete;
    IntegratorProgram& operator=(const IntegratorProgram&) = delete;

    // New settings: the kernels are rebuilt (or loaded from the cache) when the
    // features they need change, e.g. another integrator; the launch timing is
    // measured again. The acceleration structure is the scene's and cannot change.
    void set_settings(const RenderSettings& settings);
    const RenderSettings& settings() const { return settings_; }
    const KernelFeatures& features() const { return features_; }
    // The shape the kernels were built in (settings' Auto resolved for this device).
    KernelShape shape() const { return shape_; }
    double compile_seconds() const { return compile_seconds_; }
    bool compiled_from_cache() const { return from_cache_; }

    // Adds n samples per pixel to the film, of the scene seen through the
    // camera (of the film's size), in as many launches as the time target
    // asks; returns when they have finished. Nothing is rendered when the film
    // would pass kMaxSamplesPerPixel (clpath::Error).
    void add_samples(const DeviceScene& scene, Film& film, const Camera& camera, std::uint32_t n);
    // The program's film_resolve kernel, for Film::resolve_on_device.
    Kernel& resolve_kernel() { return resolve_; }
    // Its film_add_exact kernel, for DeviceExactFilm::add_chunk.
    Kernel& add_exact_kernel() { return add_exact_; }
    // Its film_add_exact_half kernel (adaptive sampling's half film), made on first use.
    Kernel& add_exact_half_kernel();

    // Adaptive sampling (render/adaptive.hpp): from the next launch on, only
    // the pixels whose byte is non-zero (one a pixel, row 0 at the top) take
    // samples, and the film's w lanes gather the half film. nullptr: every
    // pixel, w lanes untouched (the kernels' arithmetic is then exactly that of
    // a render without adaptive sampling). Throws clpath::Error when the
    // kernels (a variant's, bench render-ab) have no adaptive sampling.
    void set_active_pixels(const std::vector<std::uint8_t>* mask, std::uint32_t pixels);

    const LaunchStats& stats() const { return stats_; }
    void reset_stats() { stats_ = LaunchStats{}; }

private:
    // A launch enqueued and not yet waited for: the host copies its
    // non-blocking transfers read from and write to, and its events.
    struct PendingLaunch {
        FrameParams params{};
        Counters counters{};
        cl_event first_kernel = nullptr, counters_read = nullptr;
        double work = 0;  // pixels x samples
    };

    // The wavefront's kernels and its path state, for up to `capacity` paths.
    struct WavefrontKernels {
        Kernel camera, trace, shade, light, connect, scatter, shadow, next_bounce, accumulate;
        Buffer paths, hits, shadows, queues[2], scatter_queue, counts;
        std::uint32_t capacity = 0;
    };

    void compile();
    FrameParams frame_params(const DeviceScene& scene, const Film& film, const CameraData& camera,
                             std::uint32_t first_pixel, std::uint32_t pixel_count, std::uint32_t samples) const;
    void ensure_wavefront_buffers(std::uint32_t paths);
    // Enqueues a band's samples as waves of the wavefront kernels.
    void launch_waves(const DeviceScene& scene, Film& film, PendingLaunch& p, std::uint32_t pixel_count,
                      std::uint32_t samples);
    // Waits for a pending launch and takes its counters and time.
    void harvest(PendingLaunch& p);
    // Waits for every pending launch.
    void drain();
    void launch_band(const DeviceScene& scene, Film& film, const CameraData& camera, std::uint32_t first_pixel,
                     std::uint32_t pixel_count, std::uint32_t samples);

    Context& ctx_;
    SceneFeatures scene_features_;
    RenderSettings settings_;
    KernelFeatures features_;
    KernelShape shape_ = KernelShape::Mega;
    KernelVariant variant_;
    Buffer params_, counters_;
    Program program_;
    Kernel render_, resolve_, add_exact_, add_exact_half_;
    // The active-pixel mask, and whether the kernels take one (a variant's
    // kernels from before adaptive sampling do not).
    Buffer active_;
    bool adaptive_ = false, kernels_take_mask_ = true;
    // Binds the mask (or, without one, a placeholder the kernels never read).
    void bind_mask(Kernel& k, cl_uint index);
    WavefrontKernels wf_;
    LaunchStats stats_;
    double compile_seconds_ = 0;
    bool from_cache_ = false;
    double seconds_per_pixel_sample_ = 0;  // measured; sizes the launches
    std::array<PendingLaunch, 2> pending_;  // at most two launches in flight
    std::size_t next_slot_ = 0;
};

}  // namespace clpath
