#pragma once
// A CPU baseline for path tracing: clpath's `path` integrator (next-event
// estimation with MIS, cosine-weighted diffuse bounces) at a fixed depth
// without Russian roulette, on Embree 3 (Debian's libembree-dev), for scenes
// of Lambertian surfaces lit by emissive triangles and point, spot or
// directional lights. clpath bench path times it beside the OpenCL renderer
// on the same scene, camera and resolution, and checks that the two images
// agree within their noise. Built in when CMake finds Embree (CLPATH_WITH_EMBREE).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench/embree_scene.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct PreparedScene;

// Per-pixel sums of one render, row 0 at the top: the mean, and for the
// agreement check the per-pixel sample variance.
struct PathSums {
    int width = 0, height = 0;
    std::uint64_t spp = 0;
    std::vector<double> sum, sum_sq;  // 3 per pixel
};

struct EmbreePathRun {
    PathSums sums;
    std::uint64_t rays = 0;       // counted as the kernels count them: camera, bounce and shadow rays traced
    std::uint64_t nonfinite = 0;  // samples dropped as NaN or infinite (as the kernels drop them)
    double seconds = 0;           // wall time of the render, threads started and joined
};

// What the Embree path tracer cannot render as clpath's path integrator does
// (e.g. "material 'glass' is a dielectric"), one item per reason; empty when
// it can.
std::vector<std::string> embree_path_unsupported(const Scene& scene);

class EmbreePathTracer {
public:
    virtual ~EmbreePathTracer() = default;
    // spp samples per pixel, sample s of pixel p drawn from the random stream
    // (p, s, seed) of kernels/rng.cl.
    virtual EmbreePathRun render(std::uint32_t spp, std::uint32_t seed) = 0;
    // "Embree 3.13.5, default mode (no RTC_SCENE_FLAG_ROBUST), 2 threads on Intel(R) Xeon(R) ..., rtcIntersect1/rtcOccluded1 single rays"
    virtual std::string describe() const = 0;
    virtual EmbreeMode mode() const = 0;
};

// Whether this program was built with Embree.
bool embree_path_built_in();

// The tracer for the scene (its camera and resolution) at max_depth bounces,
// Embree in the given mode, on `threads` threads (0: every hardware thread).
// nullptr when built without Embree; throws clpath::Error for an unsupported
// scene (the reasons of embree_path_unsupported) or when Embree reports an error.
std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene& scene, std::uint32_t max_depth,
                                                          EmbreeMode mode = EmbreeMode::Default, int threads = 0);
// The same, reading the light table, materials and normals from `prepared`,
// the scene as prepare_scene made it for the renderer it is timed against
// (so neither the BVH nor the light table is built twice).
std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene& scene,
                                                          std::shared_ptr<const PreparedScene> prepared,
                                                          std::uint32_t max_depth, EmbreeMode mode = EmbreeMode::Default,
                                                          int threads = 0);

// "Intel(R) Xeon(R) Processor" from /proc/cpuinfo, or "an unknown CPU".
std::string cpu_model_name();

}  // namespace clpath
