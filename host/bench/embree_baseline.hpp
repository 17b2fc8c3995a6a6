#pragma once
// A CPU baseline for the ray-batch benchmark: Embree (Debian's libembree-dev,
// Embree 3) traces the very same rays on every core of the host, so each
// device's Mrays/s can be read against a well-known CPU tracer measured in
// the same run. Built in when CMake finds Embree (CLPATH_WITH_EMBREE).
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bench/embree_scene.hpp"
#include "shared_structs.h"

namespace clpath {

// Wall-clock times of the timed passes over a batch (after one warm-up).
struct EmbreeTiming {
    std::vector<double> pass_ms;
    double mean_ms = 0, best_ms = 0;
    double mrays_per_s = 0;  // rays / mean time
};

class EmbreeBaseline {
public:
    virtual ~EmbreeBaseline() = default;
    // Closest hit of each ray in [0, tmax]: the scene's triangle index (-1: a
    // miss) and t; in an instanced scene, (instance << 32) | the triangle's
    // index in its mesh.
    virtual EmbreeTiming closest(const std::vector<BatchRay>& rays, int passes, std::vector<std::int64_t>& prim,
                                 std::vector<float>& t) = 0;
    // Whether anything lies on each ray in [0, tmax].
    virtual EmbreeTiming any(const std::vector<BatchRay>& rays, int passes, std::vector<char>& occluded) = 0;
    // "Embree 3.13.5, default mode (no RTC_SCENE_FLAG_ROBUST), high-quality BVH, 2 threads (FTZ/DAZ), built in 812 ms"
    virtual std::string describe() const = 0;
    virtual EmbreeMode mode() const = 0;
};

// Whether this program was built with Embree.
bool embree_built_in();

// Embree's scene over vertices (three per triangle, in the scene's order) in
// the given mode, traced by `threads` threads (0: every hardware thread).
// nullptr when built without Embree; throws clpath::Error when Embree
// reports an error.
std::unique_ptr<EmbreeBaseline> make_embree_baseline(const std::vector<glm::vec3>& vertices, EmbreeMode mode,
                                                     int threads = 0);
// The same over meshes placed by instances (EmbreeScene's instanced form):
// (mesh, object-to-world) per placement.
std::unique_ptr<EmbreeBaseline> make_embree_instanced_baseline(
    const std::vector<const std::vector<glm::vec3>*>& meshes,
    const std::vector<std::pair<std::uint32_t, glm::mat4>>& placements, EmbreeMode mode, int threads = 0);

}  // namespace clpath
