#pragma once
// The triangle-count scaling benchmark (clpath bench scaling): the
// generated scaling scenes (scaling:N, the same room around one bumpy sphere
// whose size on screen stays fixed) from min to max triangles in 1-3-10
// steps. Per size and structure: generation time, build time and Mtris/s,
// SAH cost, node count, device bytes per triangle, Mrays/s of the three ray
// batches (bench/ray_batches.hpp; each from its median launch) and path
// samples/s (the median of three passes after a warm-up); beside the BVH's
// batches, Embree's default mode on the same rays (its median pass), so that
// each batch's fall with the scene's size can be read against a CPU tracer's.
// The flat structure runs until its predicted time for the next size passes
// the time cap; sizes that would not fit in memory are skipped and say why.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "bvh/accel.hpp"
#include "cl/context.hpp"

namespace clpath {

struct ScalingOptions {
    std::size_t min = 100, max = 10'000'000;
    bool bvh = true, flat = true;
    double time_cap_s = 60;           // flat: stop once the next size is predicted to take longer
    // Ray batches (x CLP_BATCH_SAMPLES): 2.5 million rays a batch, so that a
    // launch takes tens of milliseconds even at 100 triangles and three runs
    // agree within a few percent (96x64 batches, 98,304 rays, ranged 2.3-7.7
    // Mrays/s between runs at 10^6 triangles).
    int ray_width = 480, ray_height = 320;
    // Five launches, the rate from the median: on a quiet 2-core VM two of
    // three launches of a 50-100 ms batch were now and then slowed together
    // (scaling:100 diffuse 19.3 against 23.8-24.0 Mrays/s in the other two
    // runs, EPYC), which a median of three cannot outvote.
    int launches = 5;
    std::size_t check = 4096;         // rays per batch checked on the CPU
    // The path column: the renderer `clpath render` runs, at this size.
    int path_width = 320, path_height = 240;
    std::uint32_t path_spp = 4;
    // Embree (default mode, every core) traces the BVH rows' batches too, when built in.
    bool embree = true;
    // Host memory the benchmark may use; a size whose estimate exceeds it is
    // skipped. 0: 80 % of MemAvailable (/proc/meminfo).
    double memory_budget_bytes = 0;
};

struct ScalingRow {
    std::size_t requested = 0, triangles = 0;
    Accel accel = Accel::Bvh;
    std::string skipped;  // why this size was not measured; empty when it was
    double generate_ms = 0, build_ms = 0, mtris_per_s = 0, sah_cost = 0;
    std::size_t nodes = 0;
    double bytes_per_triangle = 0;  // device nodes + triangle records
    double primary_mrays = 0, shadow_mrays = 0, diffuse_mrays = 0;
    // Embree's default mode on the same batches (median pass); 0 when it did not run.
    double embree_primary_mrays = 0, embree_shadow_mrays = 0, embree_diffuse_mrays = 0;
    double msamples_per_s = 0;       // path integrator, default settings
    double path_mrays_per_s = 0;     // its rays per second, every kind
    std::size_t checked = 0, mismatched = 0;  // CPU check over the three batches
    std::size_t embree_mismatched = 0;         // Embree's answers against the same check
    double seconds = 0;              // wall time this row took
};

// The sizes: min, then 1-3-10 steps per decade, up to max.
std::vector<std::size_t> scaling_sizes(std::size_t min, std::size_t max);

// Host bytes a size is estimated to need at its peak (scene, builder, device
// copies on a CPU device, and Embree's scene when it runs).
double scaling_memory_estimate(std::size_t triangles, bool embree);

std::vector<ScalingRow> run_scaling(Context& ctx, const ScalingOptions& options,
                                    const std::function<void(const std::string&)>& log = {});

std::string scaling_csv(const std::vector<ScalingRow>& rows, const std::string& device);
std::string scaling_markdown(const std::vector<ScalingRow>& rows, const std::string& device);

}  // namespace clpath
