#pragma once
// Embree's device and scene over a triangle soup, as the CPU baselines use
// them (bench/embree_baseline.hpp, bench/embree_path_tracer.hpp): robust
// (watertight) triangles, a high-quality BVH, primID = the scene's triangle
// index. Only in builds with Embree (CLPATH_WITH_EMBREE).
#if CLPATH_WITH_EMBREE
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

namespace clpath {

class EmbreeScene {
public:
    // vertices: three per triangle, in the scene's order; threads: Embree's
    // own (for the build), 0: every hardware thread. Throws clpath::Error
    // when Embree reports an error.
    EmbreeScene(const std::vector<glm::vec3>& vertices, int threads);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    RTCScene scene() const { return scene_; }
    int threads() const { return threads_; }
    double build_ms() const { return build_ms_; }
    // Throws clpath::Error naming `what` when Embree has reported an error since the last check.
    void check(const char* what) const;

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    int threads_ = 1;
    double build_ms_ = 0;
};

// A ray from o along d (need not be unit) over (tnear, tmax]. Embree has no
// guard against the surface a ray leaves, and clpath's secondary rays can
// start exactly on it (kernels/intersect.cl hit_point, offset_ray_origin):
// Embree would report that surface at t = 0. Renderers built on Embree start
// such rays a little way along instead; here, as Mitsuba 3 does, at
// (1 + max |o_i|) 1e-6 (16 ulps of the larger of 1 and the origin's
// magnitude), so Embree traces the rays clpath traces.
void init_embree_ray(RTCRay& r, glm::vec3 o, glm::vec3 d, float tmax);

}  // namespace clpath
#endif
