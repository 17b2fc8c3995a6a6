#pragma once
// Embree's device and scene over a triangle soup, as the CPU baselines use
// them (bench/embree_baseline.hpp, bench/embree_path_tracer.hpp): a
// high-quality BVH, primID = the scene's triangle index, in one of two modes
// (EmbreeMode). Only in builds with Embree (CLPATH_WITH_EMBREE).
#include <string>

namespace clpath {

// Default: the scene flags Embree's users (and its own example renderers)
// run with: no RTC_SCENE_FLAG_ROBUST, so Embree may take its faster,
// non-watertight triangle test. Robust: RTC_SCENE_FLAG_ROBUST, watertight
// like clpath's kernels and the CPU reference (the like-for-like guarantee),
// which costs Embree speed.
enum class EmbreeMode { Default, Robust };
constexpr EmbreeMode kEmbreeModes[] = {EmbreeMode::Default, EmbreeMode::Robust};

// "default", "robust": the names in reports and CSV columns.
const char* embree_mode_name(EmbreeMode mode);
// "default mode (no RTC_SCENE_FLAG_ROBUST)", "robust mode (RTC_SCENE_FLAG_ROBUST)"
std::string describe_embree_mode(EmbreeMode mode);

// Embree asks every thread that calls rtcIntersect* or rtcOccluded* to run
// with denormals flushed to zero and read as zero (FTZ and DAZ in MXCSR),
// as without them "special handling of denormalized floating point numbers
// can significantly reduce application and Embree performance" (Embree 3
// API manual, "MXCSR control and status register"); its own tutorials, the
// `pathtracer` example among them, set both. The baselines trace as Embree's
// users are told to: each tracing thread holds one of these for the whole
// of its work. The thread's mode is restored when it goes. (Declared in
// every build: it needs nothing of Embree; a no-op where there is no MXCSR.)
class EmbreeThreadFloatMode {
public:
    EmbreeThreadFloatMode();
    ~EmbreeThreadFloatMode();
    EmbreeThreadFloatMode(const EmbreeThreadFloatMode&) = delete;
    EmbreeThreadFloatMode& operator=(const EmbreeThreadFloatMode&) = delete;

private:
    unsigned saved_ = 0;
};

}  // namespace clpath

#if CLPATH_WITH_EMBREE
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace clpath {

class EmbreeScene {
public:
    // vertices: three per triangle, in the scene's order; threads: Embree's
    // own (for the build), 0: every hardware thread. Throws clpath::Error
    // when Embree reports an error.
    EmbreeScene(const std::vector<glm::vec3>& vertices, int threads, EmbreeMode mode);
    // Instanced, as Embree's users place meshes: a scene of its own for
    // each mesh (its vertices, three per triangle, object space), placed in
    // the top-level scene by instance geometries (RTC_GEOMETRY_TYPE_INSTANCE)
    // with each placement's object-to-world map; an instance's geomID is its
    // index in placements, a hit's primID the triangle's index in its mesh.
    EmbreeScene(const std::vector<const std::vector<glm::vec3>*>& meshes,
                const std::vector<std::pair<std::uint32_t, glm::mat4>>& placements, int threads, EmbreeMode mode);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    RTCScene scene() const { return scene_; }
    int threads() const { return threads_; }
    EmbreeMode mode() const { return mode_; }
    double build_ms() const { return build_ms_; }
    // Throws clpath::Error naming `what` when Embree has reported an error since the last check.
    void check(const char* what) const;

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<RTCScene> meshes_;  // the instanced meshes' scenes

    void open(int threads, EmbreeMode mode);
    RTCScene new_scene() const;  // in mode_, high-quality BVH
    int threads_ = 1;
    EmbreeMode mode_ = EmbreeMode::Default;
    double build_ms_ = 0;
};

// A ray from o along d (need not be unit) over (tnear, tmax]. Embree has no
// guard against the surface a ray leaves, and clpath's secondary rays can
// start exactly on it (kernels/intersect.cl hit_point, offset_ray_origin):
// Embree would report that surface at t = 0. Renderers built on Embree start
// such rays a little way along instead; here, as Mitsuba 3 does, at
// (1 + max |o_i|) 1e-6 (16 ulps of the larger of 1 and the origin's
// magnitude), so Embree traces the rays clpath traces. length: |d|, when the
// caller knows it (1 for a unit direction).
//
// Origin and tnear, direction and time are each written as one 16-byte
// store: Embree's rtcIntersect1/rtcOccluded1 read them as two 16-byte loads
// straight away, and a load that spans several narrower stores still in
// the store buffer cannot be forwarded from them (a store-forwarding stall:
// Intel's optimization manual, "Store Forwarding"). Written field by field,
// those two loads were the hottest instructions of the built-in path
// tracer's Embree time (perf), and took next to nothing in Embree's own
// `pathtracer` example, whose Vec3fa rays are written whole
// (benchmarks/results/pocl-xeon-2core/path-embree-pathtracer/README.md).
inline void init_embree_ray(RTCRay& r, glm::vec3 o, glm::vec3 d, float tmax, float length) {
    const float mag = std::max(std::fabs(o.x), std::max(std::fabs(o.y), std::fabs(o.z)));
    const float tnear = length > 0 ? (1.0f + mag) * 1e-6f / length : 0.0f;
    static_assert(offsetof(RTCRay, tnear) == 12 && offsetof(RTCRay, dir_x) == 16 && offsetof(RTCRay, time) == 28,
                  "RTCRay begins org, tnear, dir, time");
#if defined(__SSE__)
    _mm_store_ps(&r.org_x, _mm_setr_ps(o.x, o.y, o.z, tnear));  // RTCRay is 16-byte aligned (RTC_ALIGN(16))
    _mm_store_ps(&r.dir_x, _mm_setr_ps(d.x, d.y, d.z, 0.0f));
#else
    r.org_x = o.x;
    r.org_y = o.y;
    r.org_z = o.z;
    r.tnear = tnear;
    r.dir_x = d.x;
    r.dir_y = d.y;
    r.dir_z = d.z;
    r.time = 0.0f;
#endif
    r.tfar = tmax;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
}
inline void init_embree_ray(RTCRay& r, glm::vec3 o, glm::vec3 d, float tmax) {
    init_embree_ray(r, o, d, tmax, glm::length(d));
}

}  // namespace clpath
#endif
