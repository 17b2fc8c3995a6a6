#pragma once
// The ray-batch traversal benchmark (clpath bench rays), made to be
// comparable with published GPU traversal tests (tinybvh's):
// width x height pixels x CLP_BATCH_SAMPLES (16) samples on a 4x4 sub-pixel
// grid, rays ordered in 4x4-pixel tiles (kernels/shared_structs.h); a batch of primary rays (closest hit), of shadow rays from
// the primary hits to a point light (any hit) and of cosine-distributed
// diffuse rays from the primary hits (closest hit). Each batch: one warm-up
// and N timed launches, timed by OpenCL profiling events; every batch is
// checked against a CPU reference traversal (bench/cpu_traversal.hpp).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bench/ab_ratios.hpp"
#include "bench/embree_scene.hpp"
#include "bench/ray_files.hpp"
#include "bvh/accel.hpp"
#include "cl/context.hpp"
#include "cl/embedded_sources.hpp"
#include "cl/kernel_info.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct RayBenchOptions {
    int width = 480, height = 320;  // multiples of CLP_BATCH_TILE
    int launches = 5;               // timed launches per batch, after one warm-up
    std::size_t workgroup = 64;     // work-items per group; 0: the driver chooses
    Accel accel = Accel::Bvh;
    std::optional<glm::vec3> light;  // default: default_bench_light(scene)
    std::size_t check = std::size_t(1) << 18;  // rays per batch checked on the CPU (evenly spaced); 0: all
    std::uint32_t seed = 0;                    // diffuse directions
    BvhBuildOptions bvh;
    // Trace every batch with Embree too, in its default mode and robust
    // (bench/embree_scene.hpp), when built with it (bench/embree_baseline.hpp);
    // in its default mode only without embree_robust.
    bool embree = true;
    bool embree_robust = true;
    // A variant of the kernels to time against the built-in ones (kernel
    // files replacing built-in ones, build options added). Each batch's launches then
    // alternate between the two programs, which goes first alternating too,
    // so that a drift in the machine's speed weighs on both alike
    // (BatchResult::ab). Empty: off.
    KernelVariant ab;
    // Hears each batch's rays and the device's answers once it is traced (for
    // --save-rays: bench/ray_files.hpp); empty batches too. May be empty.
    std::function<void(RayBatchKind, const std::vector<BatchRay>&, const std::vector<float>& result)> on_traced;
    // Hears, once and before any batch is traced, the batch kernels' program
    // (source and build options) and the node and triangle buffers they
    // traverse (for --save-rays: bench/ray_files.hpp). May be empty.
    std::function<void(const std::string& source, const std::string& options, const std::vector<unsigned char>& nodes,
                       const BvhTriangles& triangles)>
        on_structure;
};

// How a batch's device results compare with the CPU reference.
struct BatchAgreement {
    std::size_t checked = 0;
    std::size_t identical = 0;   // same triangle (or both miss; for any-hit: same occluded flag)
    std::size_t ties = 0;        // closest hit: another triangle at the same distance (see kTieTolerance)
    std::size_t near_origin = 0; // one side's hit lies within kNearOrigin of the ray's origin (see there)
    std::size_t mismatched = 0;  // none of these
    double max_dt = 0;           // largest |t_device - t_cpu| over identical hits (scene units, |d| = 1 for closest-hit batches)
    std::string first_mismatch;  // the first mismatched ray, for a report: index, origin, direction, both answers
    double identical_percent() const { return checked ? 100.0 * double(identical) / double(checked) : 100.0; }
    bool agrees() const { return mismatched == 0; }
};

// A tie is two triangles whose distances differ by at most this times
// (t + the largest origin coordinate), the magnitude float rounding of t
// scales with: far above the float test's rounding error (a few gamma(7) ~
// 1e-6 relative, PBR 4th ed. 6.8), far below the gap between two surfaces
// of the scenes measured.
constexpr double kTieTolerance = 1e-5;

// A secondary ray that leaves a surface right next to another (a corner) can
// meet that other surface within the rounding-error bound the device's
// triangle test puts on t (PBR 4th ed. 6.8.3: about 2e-5 at unit scale); the
// device then rejects the hit as possibly behind the origin, the exact CPU
// test accepts it. Such differences (hit distance below kNearOrigin times
// the scale above) are counted apart from mismatches.
constexpr double kNearOrigin = 1e-4;

// The same batch traced by Embree on the host's cores (wall-clock time of
// each pass), checked against the CPU reference like the device.
struct EmbreeBatch {
    bool ran = false;
    EmbreeMode mode = EmbreeMode::Default;
    std::size_t hits = 0;
    double best_ms = 0, mean_ms = 0;
    double median_ms = 0;    // the middle pass (the mean of the middle two for an even count)
    double mrays_per_s = 0;  // rays / mean time
    BatchAgreement agreement;
};

struct BatchResult {
    std::string name;  // primary, shadow, diffuse
    std::size_t rays = 0, hits = 0;
    std::vector<double> launch_ms;  // each timed launch's kernel time
    double best_ms = 0, mean_ms = 0;
    double median_ms = 0;    // the middle launch (the mean of the middle two for an even count)
    double mrays_per_s = 0;  // rays / mean kernel time
    BatchAgreement agreement;
    EmbreeBatch embree[2];  // by EmbreeMode: default, robust
    AbResult ab;
    const EmbreeBatch& embree_in(EmbreeMode m) const { return embree[int(m)]; }
    // The device's Mrays/s over Embree's in that mode; 0 when Embree did not run.
    double over_embree(EmbreeMode m) const {
        const EmbreeBatch& e = embree_in(m);
        return e.ran && e.mrays_per_s > 0 ? mrays_per_s / e.mrays_per_s : 0;
    }
};

struct RayBenchResult {
    std::string scene;
    std::size_t triangles = 0;
    Accel accel = Accel::Bvh;
    BvhStats structure;  // of the structure traversed
    std::size_t structure_bytes = 0;  // nodes + triangles on the device
    glm::vec3 light{0};
    std::string device;
    std::vector<BatchResult> batches;  // primary, shadow, diffuse
    std::vector<KernelInfo> kernels;   // the batch kernels on this device
    std::string embree[2];             // the baselines' descriptions by EmbreeMode; empty when they did not run
};

// The point light a scene is benchmarked with when none is given: its first
// point light; else just below the area-weighted centre of its emitters (a
// ceiling lamp); else above the middle of its bounding box.
glm::vec3 default_bench_light(const Scene& scene);

// Runs the three batches on ctx's device for scene.camera (width and height
// from options). log (may be empty) hears progress lines. Throws clpath::Error
// for bad options or a scene too large for the device.
RayBenchResult run_ray_bench(Context& ctx, const Scene& scene, const RayBenchOptions& options,
                             const std::function<void(const std::string&)>& log = {});

// "primary: 2457600 rays (786432 hit), 12.3 ms, 199.8 Mrays/s; CPU check: 262144 rays, 100.000 % identical, ..."
std::string describe(const BatchResult& batch);
// "  Embree default mode: 40.1 ms mean / 39.8 ms best, 61.29 Mrays/s, clpath/Embree 0.39; CPU check: ..."
std::string describe_embree(const BatchResult& batch, EmbreeMode mode);
// The A/B line under it: "  A/B: variant/built-in 1.03 (quartiles 0.99-1.05) over 10
// launch pairs; answers differ for 0 rays"; empty when no variant ran.
std::string describe_ab(const BatchResult& batch);

}  // namespace clpath
