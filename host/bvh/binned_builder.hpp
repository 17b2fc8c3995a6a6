#pragma once
// The binned-SAH builder behind build_bvh (bvh.hpp): a binary tree over
// triangle references, before flattening into the device layout.
//
// Memory: one 32-byte record per triangle (its box and index), and a second
// array of them: a split scatters its node's records from one to the other
// (a median split reorders them in place); a leaf's end in the first. The
// tree's nodes live in one array allocated up front. A subtree over n
// triangles whose root is slot s owns slots [s, s + 2n - 1) (a binary tree
// with at least one triangle per leaf has at most 2n - 1 nodes): its left
// subtree starts at s + 1, its right at s + 2 * (left triangle count). So no
// node is allocated on the heap, threads never share a slot, and the tree's
// layout does not depend on which thread built what.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/big_arrays.hpp"
#include "bvh/bvh.hpp"

namespace clpath::bvh_build {

struct alignas(16) Ref {
    float lo[3];
    std::uint32_t prim;  // the triangle's index in the input
    float hi[3];
    float pad;
};

// 32 bytes: two to a cache line.
struct TreeNode {
    float lo[3], hi[3];
    std::uint32_t link;   // leaf: its first record; interior: the right child's slot (the left's is the next)
    std::uint32_t count;  // leaf: records; 0 for an interior node
};
static_assert(sizeof(TreeNode) == 32);

// A subtree one thread built whole (the tree above them: the large nodes).
struct Subtree {
    std::uint32_t slot = 0, begin = 0;
    int depth = 1;           // of its root, the tree's root = 1
    std::size_t leaves = 0;  // in it
};

struct Tree {
    BigArray<TreeNode> nodes;  // slot 0 is the root; unused slots are left unwritten
    BigArray<Ref> refs;        // in leaf order
    std::size_t ref_count = 0;
    std::size_t leaf_count = 0;
    std::vector<Subtree> subtrees;  // left to right (by first record)
    std::size_t top_interior = 0;   // interior nodes above the subtrees
};

// options: validated, threads >= 1. Throws clpath::Error for a non-finite vertex.
Tree build_tree(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options);

// f(t) for t in [0, threads): t = 0 on the calling thread, the others on their own.
// Throws clpath::Error when a thread cannot be started.
void fork_join(int threads, const std::function<void(int)>& f);

}  // namespace clpath::bvh_build
