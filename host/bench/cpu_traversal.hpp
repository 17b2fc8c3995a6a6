#pragma once
// The reference the ray-batch benchmark checks the device against: a CPU walk
// of a BVH in double precision (Moller & Trumbore's ray/triangle test, edges
// inclusive, and slab tests), independent of the kernels' float arithmetic.
// With ~29 more bits than the float inputs it finds the exact closest
// triangle except at ties (a ray through a shared edge or vertex).
#include <cstdint>

#include "bvh/bvh.hpp"
#include "shared_structs.h"

namespace clpath {

struct CpuHit {
    double t = 0;
    std::int64_t prim = -1;  // the scene's triangle index (TriVerts::prim); -1: a miss
};

// Closest hit in (0, ray.tmax) over a BVH in the tree layout (build_bvh);
// with at_origin, in [0, ray.tmax): a triangle through the origin counts too.
CpuHit cpu_closest_hit(const Bvh& bvh, const BatchRay& ray, bool at_origin = false);
// Any hit in (0, ray.tmax): the occluding triangle's index, or -1.
std::int64_t cpu_any_hit(const Bvh& bvh, const BatchRay& ray);

}  // namespace clpath
