#pragma once
// The binned-SAH builder behind build_bvh (bvh.hpp): the device's binary
// layout (BvhNode64, a node holding its two children's boxes) written as the
// tree is built, with no intermediate tree to flatten.
//
// Memory: one 32-byte record per triangle (its box and index), and a second
// array of them, in storage the caller lends (build_bvh: the output
// triangles', not yet written): a split scatters its node's records from
// one to the other (a median split reorders them in place); a leaf's end in
// the first. The nodes over many triangles (the top levels, built by all
// threads together) are kept apart and numbered level by level; each smaller
// subtree is built by one thread, numbered depth first (a node, its left
// subtree, its right), into a scratch block of ~1 MiB that stays in its
// thread's cache, and moved into the output once every subtree started
// before it has been. So threads never share a node, the output is written
// once, and the layout does not depend on which thread built what.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/big_arrays.hpp"
#include "bvh/bvh.hpp"
#include "bvh/records.hpp"

namespace clpath::bvh_build {

struct Tree {
    BigArray<Ref> refs;  // in leaf order
    std::size_t ref_count = 0;
    std::size_t node_count = 0;  // BvhNode64s
    std::size_t leaf_count = 0;
    int max_depth = 0;    // of the BvhNode64s, the root = 1
    double sah_cost = 0;  // over the root's area
};

// options: validated, threads >= 1. Writes the tree into nodes[0,
// node_count) (nodes is left longer: room for the most nodes the tree could
// have had; the caller shrinks it). scatter: room for one record per
// triangle, the second array of records, left holding nothing of use.
// Throws clpath::Error for a non-finite vertex.
Tree build_tree(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options, BvhNodes& nodes,
                Ref* scatter);

}  // namespace clpath::bvh_build
