#pragma once
// Rays traced on the test device through the renderer's own traversal code
// (tests/kernels/probes.cl): through a BVH, and against every triangle
// without one (the reference the BVH and the structures built on it must
// equal). Rays are 6 floats each: origin, direction.
#include <vector>

#include <glm/glm.hpp>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"

namespace clpath::test {

struct Traced {
    std::vector<float> t;     // closest hit distance, INFINITY (or tmax) for a miss
    std::vector<int> prim;    // the hit triangle's scene index, -1 for a miss
    std::vector<int> any;     // any-hit answer (trace_bvh only)
};

// Closest and any hit through the BVH, each ray bounded by its tmax.
Traced trace_bvh(const Bvh& bvh, const std::vector<float>& rays, const std::vector<float>& tmax);

// Closest hit against every triangle in turn.
Traced trace_brute(const BvhTriangles& tris, const std::vector<float>& rays);

// A triangle soup (3 vertices each) as device triangles whose prim is their index.
BvhTriangles device_triangles(const std::vector<glm::vec3>& verts);

}  // namespace clpath::test
