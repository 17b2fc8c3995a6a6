#pragma once
// One render of a scene to a sample count or a time budget, the way a program
// embedding clpath runs it: chunks of samples over every chosen device and,
// with a ProcessGroup, over every process of a job; checkpoints written as it
// goes, and resuming from one. The caller shows progress and decides when to
// stop (hooks); the image is the same bits however the work was split.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bvh/bvh.hpp"
#include "bvh/instances.hpp"
#include "cl/device.hpp"
#include "render/device_farm.hpp"
#include "render/exact_film.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

class ProcessGroup;

struct SessionOptions {
    std::uint64_t spp = 0;            // 0: until the time budget is spent
    double time_limit = 0;            // seconds; 0: none
    std::uint32_t chunk_samples = 0;  // 0: default_chunk_samples(spp)
    double checkpoint_seconds = 0;    // 0: no checkpoints
    std::string checkpoint_path;      // where checkpoints go
    std::string resume_path;          // a checkpoint to continue from; empty: none
    // Adaptive sampling (render/adaptive.hpp): > 0, pixels whose error
    // estimate is below it stop taking samples, and the render ends when all
    // have (or at spp or time_limit). Chunks are then of an even number of samples.
    double noise_target = 0;
    // For tests: replaces the decision rule (adaptive_active_pixels), e.g. with
    // one known to be biased, to show that the agreement tests catch it.
    std::function<std::vector<std::uint8_t>(const ExactFilm&, std::uint64_t min_samples)> adaptive_rule;
};

// All optional; called on the calling thread, but on_chunk.
struct SessionHooks {
    // Once, when a resumed checkpoint has been read and checked, with its
    // samples per pixel.
    std::function<void(std::uint64_t spp)> on_resumed;
    // Once, when the scene is prepared and before the devices start.
    std::function<void(const BvhStats&)> on_start;
    // About every 10 ms while rendering, with the film's samples per pixel.
    std::function<void(std::uint64_t spp)> on_progress;
    // Asked as often: true ends the render, keeping the chunks finished so
    // far (and, with checkpoints on, saving them in a last checkpoint).
    std::function<bool()> stop_requested;
    // On a device's own thread, after each chunk it adds, with the film's
    // samples per pixel.
    std::function<void(std::uint64_t spp)> on_chunk;
};

struct SessionResult {
    ExactFilm film;                   // on the lead (or alone): the whole image's sums (and, adaptive, per-pixel counts)
    std::vector<DeviceShare> shares;  // per device (on the lead, of every process)
    BvhStats bvh;
    bool instanced = false;           // the scene places meshes by instances: a two-level BVH
    TwoLevelStats instances;          // ... what it holds and what it took to build
    LightBvhSummary light_bvh;        // the light BVH, when the scene was prepared with it
    std::size_t scene_device_bytes = 0;  // the scene's buffers on one device
    bool stopped = false;             // stop_requested() ended it early
    std::uint64_t resumed_spp = 0;    // samples per pixel the resumed checkpoint held (0: not resumed)
    bool converged = false;           // adaptive: every pixel reached the noise target
    double wall_seconds = 0;          // from the first chunk: compiles and uploads are not in it
    std::uint64_t rays = 0, nonfinite = 0;
    std::uint64_t bytes_to_device = 0, bytes_from_device = 0;  // every device's, scene uploads included
    bool leads = true;                // false on processes of a group other than the lead
};

SessionResult render_session(const Scene& scene, const RenderSettings& settings,
                             const std::vector<DeviceInfo>& devices, const SessionOptions& options,
                             const SessionHooks& hooks = {}, ProcessGroup* group = nullptr);

}  // namespace clpath
