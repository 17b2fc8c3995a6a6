#pragma once
// The instancing benchmark (clpath bench instances): the ray batches of
// bench rays (primary, shadow to a point light, diffuse; bench/ray_batches.hpp)
// on a scene that places meshes by instances, traced by clpath's two-level
// walk, by clpath's one-level BVH over the same scene flattened (where it
// fits), and by Embree over the instances (rtcNewScene per mesh, instance
// geometries) and flattened, each in its default mode and robust. All trace
// the same rays; each tracer's answers are compared with the two-level
// walk's, ray by ray.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.hpp"
#include "bvh/instances.hpp"
#include "cl/context.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct InstanceBenchOptions {
    int width = 480, height = 320;   // multiples of CLP_BATCH_TILE
    int launches = 5;                // timed launches (or Embree passes) per batch, after one warm-up
    std::size_t workgroup = 64;      // work-items per group; 0: the driver chooses
    std::optional<glm::vec3> light;  // default: default_bench_light of the flattened scene's emitters, or above it
    std::uint32_t seed = 0;          // diffuse directions
    BvhBuildOptions bvh;
    bool embree = true;              // when built with it
    // The flattened scene is traced too while it places at most this many
    // triangles (10,000 bunnies, 7e8, would take 34 GB).
    std::size_t flatten_limit = 50'000'000;
};

// The tracers, in report order.
enum class InstanceTracer {
    Instanced,                // clpath, the two-level walk
    Flattened,                // clpath, the one-level BVH over the flattened scene
    EmbreeInstancedDefault,   // Embree, instances, default mode
    EmbreeInstancedRobust,    // Embree, instances, RTC_SCENE_FLAG_ROBUST
    EmbreeFlattenedDefault,
    EmbreeFlattenedRobust,
};
constexpr std::size_t kInstanceTracers = 6;
const char* instance_tracer_name(InstanceTracer t);  // "clpath instanced", ..., "Embree flattened robust"

// One tracer's pass over one batch.
struct TracerPass {
    bool ran = false;
    double mean_ms = 0, best_ms = 0, mrays_per_s = 0;  // device: OpenCL events; Embree: wall clock on every core
    std::size_t hits = 0;
    // Rays whose answer is not the two-level walk's: hit against miss (for
    // shadow rays, occluded against not), or both hit beyond kTieTolerance of
    // each other; hits within kNearOrigin of the origin (bench/ray_batches.hpp)
    // are counted in near_origin instead.
    std::size_t differing = 0, near_origin = 0;
};

struct InstanceBatch {
    std::string name;  // primary, shadow, diffuse
    std::size_t rays = 0;
    std::array<TracerPass, kInstanceTracers> by;
    const TracerPass& of(InstanceTracer t) const { return by[std::size_t(t)]; }
    // clpath's two-level walk against tracer t, in rays per second (0 when t did not run).
    double ratio(InstanceTracer t) const;
};

struct InstanceBenchResult {
    std::string scene, device;
    std::size_t instances = 0, stored_triangles = 0, placed_triangles = 0;
    TwoLevelStats two_level;
    std::size_t instanced_bytes = 0;  // two-level nodes, instance records and stored triangles
    bool flattened = false;
    std::string not_flattened;        // why not, when not
    double flattened_build_ms = 0;
    std::size_t flattened_bytes = 0;  // one-level nodes and placed triangles
    glm::vec3 light{0};
    std::array<std::string, kInstanceTracers> baselines;  // Embree's descriptions, where it ran
    std::vector<InstanceBatch> batches;
};

// Throws clpath::Error for a scene without instances, a bad size, or what
// the device or Embree refuse. log (may be empty) hears the progress.
InstanceBenchResult run_instance_bench(Context& ctx, const Scene& scene, const InstanceBenchOptions& o,
                                       const std::function<void(const std::string&)>& log);

// One line per batch: every tracer's Mrays/s, the ratios and the differing rays.
std::string describe(const InstanceBatch& b);

}  // namespace clpath
