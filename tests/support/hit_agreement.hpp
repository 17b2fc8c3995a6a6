#pragma once
// Whether two traversals that report different triangles for one ray are
// both right: only when each triangle, intersected alone by the kernels' own
// triangle test (tests/kernels/probes.cl, probe_brute), is hit at exactly the
// reported distance, a tie (a ray through a shared edge or vertex, or
// coincident triangles). A mislabelled triangle or one at another distance
// fails it.
#include <vector>

#include "bvh/bvh.hpp"
#include "support/random_geometry.hpp"

namespace clpath::test {

// tris[p] is the scene's triangle p (device_triangles); prims of -1 are misses.
bool same_hit_or_exact_tie(const BvhTriangles& tris, const TestRay& ray, int prim_a, int prim_b, float t);

}  // namespace clpath::test
