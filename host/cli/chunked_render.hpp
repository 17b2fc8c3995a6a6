#pragma once
// The render command's engine: chunks of samples over every chosen device
// and, under MPI, every rank; time budget, Ctrl-C, checkpoints and resume.
#include <cstdint>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "cli/progress.hpp"
#include "render/device_farm.hpp"
#include "render/exact_film.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

class MpiJob;

struct ChunkedRenderOptions {
    std::uint64_t spp = 0;        // 0: until the time budget is spent
    double time_limit = 0;        // seconds; 0: none
    std::uint32_t chunk_samples = 0;  // 0: default_chunk_samples(spp)
    double checkpoint_seconds = 0;    // 0: no checkpoints
    std::string checkpoint_path;      // where checkpoints go
    std::string resume_path;          // a checkpoint to continue from; empty: none
    bool progress = true;
    double progress_interval = kDefaultProgressInterval;  // seconds: the longest gap between lines in a log
};

struct ChunkedRenderResult {
    ExactFilm film;                   // on rank 0 (or without MPI): the whole image's sums
    std::vector<DeviceShare> shares;  // per device (on rank 0, of every rank)
    BvhStats bvh;
    bool interrupted = false;
    int signal = 0;
    double wall_seconds = 0;
    std::uint64_t rays = 0, nonfinite = 0;
    bool writes_output = true;  // false on MPI ranks other than 0
};

ChunkedRenderResult render_in_chunks(const Scene& scene, const RenderSettings& settings,
                                     const std::vector<DeviceInfo>& devices, const ChunkedRenderOptions& options,
                                     MpiJob* mpi);

}  // namespace clpath
