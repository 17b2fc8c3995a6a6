#pragma once
// The bounding volume hierarchy: a binned-SAH builder over triangle bounds,
// flattened into the device layout of kernels/shared_structs.h.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared_structs.h"

namespace clpath {

struct BvhBuildOptions {
    int max_leaf_size = 4;        // triangles per leaf at most
    int bins = 16;                // SAH bins per axis
    int threads = 0;              // 0: all hardware threads
    float traversal_cost = 1.0f;  // SAH cost of a node visit; a triangle test costs 1
};

struct BvhStats {
    double build_ms = 0;
    std::size_t node_count = 0;  // BvhNode64 records (each holds two children)
    std::size_t leaf_count = 0;
    int max_depth = 0;    // in BvhNode64 levels, root = 1
    double sah_cost = 0;  // SAH cost normalised by the root's surface area
};

struct Bvh {
    std::vector<BvhNode64> nodes;       // nodes[0] is the root
    std::vector<TriVerts> triangles;  // in leaf order; .prim is the scene's triangle index
    BvhStats stats;
};

// The most triangles a BVH can hold: leaves store ~first in a 32-bit int.
constexpr std::size_t kMaxBvhTriangles = 0x7fffffff;

// vertices: three per triangle. Deterministic: the same input gives the same
// tree whatever the thread count. Throws clpath::Error for no triangles, more
// than kMaxBvhTriangles, a non-finite vertex, or options out of range (bins
// in [2, 256], leaf size in [1, 64], traversal cost finite and >= 0).
Bvh build_bvh(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options = {});

// "BVH: 97 nodes, 60 leaves, depth 9, SAH cost 21.3, built in 0.1 ms"
std::string describe(const BvhStats& stats);

// Throws std::logic_error naming the first broken invariant: boxes contain
// everything below them (exactly), every triangle is referenced once, every
// node is reached once, depth <= CLP_BVH_MAX_DEPTH.
void check_bvh(const Bvh& bvh, std::size_t triangle_count);

}  // namespace clpath
