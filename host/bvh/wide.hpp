#pragma once
// The BVH as the kernels traverse it: the binary tree of bvh.hpp collapsed
// into nodes of four children (Bvh4Node128, kernels/shared_structs.h: what
// GPUs and instanced scenes walk) or eight (Bvh8Node256: what CPUs walk,
// bvh/accel.hpp's NodeLayout). Each wide node takes its binary node's children, then splits the largest remaining
// interior child while there is room (the collapse of Wald, Benthin and
// Boulos 2008, "Getting rid of packets"). The child boxes are the binary
// tree's boxes, bit for bit, and the triangles keep their leaf order, so hits
// index the same triangles.
#include <cstddef>
#include <vector>

#include "bvh/bvh.hpp"

namespace clpath {

// How a wide node chooses the binary nodes it opens.
enum class WideningRule {
    // Always the interior child of largest surface area: fewer node fetches
    // than the rule below (faster on every ray batch measured), but a wide
    // level may span a single binary level.
    LargestFirst,
    // Every interior child first, then the largest: each wide level spans at
    // least two binary levels, so a tree within CLP_BVH_MAX_DEPTH always
    // gives one within CLP_BVH4_MAX_DEPTH.
    TwoLevels,
};

// binary: a tree as build_bvh makes it (nodes[0] the root). LargestFirst
// falls back to TwoLevels for a tree it would widen deeper than
// CLP_BVH4_MAX_DEPTH (the traversal stack's bound), so the result fits
// whenever the binary tree is within CLP_BVH_MAX_DEPTH (check_wide tells).
// Throws std::invalid_argument for no nodes.
std::vector<Bvh4Node128> widen_bvh(const BvhNodes& binary,
                                WideningRule rule = WideningRule::LargestFirst);
// The same into nodes of eight, within CLP_BVH8_MAX_DEPTH.
std::vector<Bvh8Node256> widen_bvh8(const BvhNodes& binary, WideningRule rule = WideningRule::LargestFirst);

// Returns the depth (root = 1). Throws std::logic_error naming the first
// broken invariant: every child box contains everything below it (exactly),
// every triangle of bvh is in one leaf, every node is reached once, empty
// slots only after full ones, and the depth is within CLP_BVH4_MAX_DEPTH
// (CLP_BVH8_MAX_DEPTH for eight).
int check_wide(const std::vector<Bvh4Node128>& wide, const Bvh& bvh);
int check_wide(const std::vector<Bvh8Node256>& wide, const Bvh& bvh);

}  // namespace clpath
