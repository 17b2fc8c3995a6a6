#pragma once
// The BVH as the kernels traverse it: the binary tree of bvh.hpp collapsed
// into nodes of four children (Bvh4Node, kernels/shared_structs.h). Each wide
// node takes its binary node's children and, where they are interior, their
// children in turn, then splits the largest remaining interior child while
// there is room (the collapse of Wald, Benthin and Boulos 2008, "Getting rid
// of packets"). The child boxes are the binary tree's boxes, bit for bit, and
// the triangles keep their leaf order, so hits index the same triangles.
#include <cstddef>
#include <vector>

#include "bvh/bvh.hpp"

namespace clpath {

// binary: a tree as build_bvh makes it (nodes[0] the root). Every wide level
// spans at least two binary levels, so a tree within CLP_BVH_MAX_DEPTH gives
// one within CLP_BVH4_MAX_DEPTH. Throws std::invalid_argument for no nodes.
std::vector<Bvh4Node> widen_bvh(const std::vector<BvhNode>& binary);

// Returns the depth (root = 1). Throws std::logic_error naming the first
// broken invariant: every child box contains everything below it (exactly),
// every triangle of bvh is in one leaf, every node is reached once, empty
// slots only after full ones, and the depth is within CLP_BVH4_MAX_DEPTH.
int check_wide(const std::vector<Bvh4Node>& wide, const Bvh& bvh);

}  // namespace clpath
