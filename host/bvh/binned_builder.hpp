#pragma once
// The binned-SAH builder behind build_bvh (bvh.hpp): the device's binary
// layout (BvhNode64, a node holding its two children's boxes) written as the
// tree is built, with no intermediate tree to flatten.
//
// Memory: one 32-byte record per triangle (its box and index), and a second
// array of them, in storage the caller lends (build_bvh: the output
// triangles', not yet written): a split scatters its node's records from one to the other
// (a median split reorders them in place); a leaf's end in the first. The
// nodes over many triangles (the top levels, built by all threads together)
// are kept apart and numbered level by level; each smaller subtree is built
// by one thread, numbered depth first (a node, its left subtree, its right),
// into a block of the output reserved for the most nodes it can have (one
// fewer than its triangles), and the blocks are then packed left to right
// (compact_blocks). So no node is allocated on the heap, threads never share
// a node, and the layout does not depend on which thread built what.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/big_arrays.hpp"
#include "bvh/bvh.hpp"
#include "bvh/fork_join.hpp"
#include "bvh/records.hpp"

namespace clpath::bvh_build {

// A subtree's nodes as built, at nodes[from, from + count), their interior
// children numbered from 0 within it; they belong at nodes[to, to + count).
struct Block {
    std::size_t from = 0, to = 0, count = 0;
};

struct Tree {
    BigArray<Ref> refs;  // in leaf order
    std::size_t ref_count = 0;
    std::size_t node_count = 0;  // BvhNode64s, once the blocks are packed
    std::size_t leaf_count = 0;
    int max_depth = 0;    // of the BvhNode64s, the root = 1
    double sah_cost = 0;  // over the root's area
    std::vector<Block> blocks;  // left to right; to <= from, increasing
};

// options: validated, threads >= 1. Writes the nodes above the subtrees and
// each subtree's block into nodes (resized to what the blocks need before
// packing). scatter: room for one record per triangle, the second array of
// records, left holding nothing of use. Throws clpath::Error for a non-finite vertex.
Tree build_tree(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options, BvhNodes& nodes,
                Ref* scatter);

// Moves the blocks to where they belong, left to right (each moves left, so
// one pass in order overwrites nothing still to be read), offsetting their
// interior children. nodes[0, tree.node_count) is then the tree.
void compact_blocks(const Tree& tree, BvhNodes& nodes);

}  // namespace clpath::bvh_build
