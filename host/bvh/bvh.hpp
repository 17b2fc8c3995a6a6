#pragma once
// The bounding volume hierarchy: a binned-SAH builder over triangle bounds,
// writing the device layout of kernels/shared_structs.h.
#include <cstddef>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/big_arrays.hpp"
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

// std::allocator, except that what resize(n) and emplace_back() add is left
// uninitialised (default-initialised): the builder writes every element
// itself, from several threads, and zero-filling tens of MiB first was a
// single-threaded pass over fresh pages (room:1003542, Xeon: 13-20 ms of a
// 330 ms build). Code that wants zeros says so: resize(n, BvhNode64{}).
// From 2 MiB up, aligned to huge pages and advised to use them, as the
// builder's own arrays (bvh/big_arrays.hpp): unaligned, a 4 MiB node array
// took ~800 more page faults per build on bunny (70k triangles).
template <class T>
struct UninitAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitAllocator<U>;
    };
    UninitAllocator() = default;
    template <class U>
    UninitAllocator(const UninitAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n * sizeof(T) < bvh_build::kHugePage) return std::allocator<T>::allocate(n);
        return bvh_build::big_array<T>(n).release();
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < bvh_build::kHugePage)
            std::allocator<T>::deallocate(p, n);
        else
            bvh_build::FreeDelete{}(p);
    }
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
using BvhNodes = std::vector<BvhNode64, UninitAllocator<BvhNode64>>;
using BvhTriangles = std::vector<TriVerts, UninitAllocator<TriVerts>>;

struct Bvh {
    BvhNodes nodes;          // nodes[0] is the root
    BvhTriangles triangles;  // in leaf order; .prim is the scene's triangle index
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
