#pragma once
// clpath bench path: clpath's renderer (the `path` integrator at a fixed
// depth, no Russian roulette, on an OpenCL device) and the Embree path tracer
// (bench/embree_path_tracer.hpp), Embree in its default mode and robust
// (bench/embree_scene.hpp), render the same scene in interleaved rounds;
// their speeds, and whether their images agree within their noise
// (bench/path_agreement.hpp).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bench/path_agreement.hpp"
#include "cl/context.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct PathBenchOptions {
    std::uint32_t spp = 16;
    std::uint32_t max_depth = 4;
    int rounds = 3;
    // clpath renders with this seed, Embree with seed + 1: independent streams,
    // as the agreement check assumes.
    std::uint32_t seed = 0;
    int threads = 0;  // Embree's; 0: every hardware thread
    int grid = 4;     // regions per side for the agreement check
};

// One tracer's run in one round.
struct PathTiming {
    double seconds = 0;
    std::uint64_t rays = 0, nonfinite = 0;
    double msamples_per_s = 0, mrays_per_s = 0;
};

struct PathRound {
    PathTiming clpath;
    PathTiming embree[2];  // by EmbreeMode: default, robust
    double samples_ratio(EmbreeMode m) const;  // clpath / Embree in mode m, Msamples/s
    double rays_ratio(EmbreeMode m) const;     // clpath / Embree in mode m, Mrays/s
};

struct PathBenchResult {
    std::string scene, clpath_device;
    std::string embree[2];  // the Embree tracers' descriptions, by EmbreeMode
    std::size_t triangles = 0;
    int width = 0, height = 0;
    std::uint32_t spp = 0, max_depth = 0;
    std::vector<PathRound> rounds;
    PathAgreement agreement[2];  // clpath's last image against each Embree tracer's, by EmbreeMode
    bool agrees() const { return agreement[0].agrees() && agreement[1].agrees(); }
};

// Throws clpath::UsageError naming what the Embree tracer cannot render as
// clpath does (other materials, textures, an environment...), clpath::Error
// when this build has no Embree. Needs no device.
void check_path_bench_scene(const Scene& scene);

// Throws what check_path_bench_scene throws, and clpath::Error when a step fails.
PathBenchResult run_path_bench(Context& ctx, const Scene& scene, const PathBenchOptions& options,
                               const std::function<void(const std::string&)>& log);

}  // namespace clpath
