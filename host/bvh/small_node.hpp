#pragma once
// Nodes over a few triangles, split without bins: the decision and the
// partition the binned path (binned_builder.cpp: bin_refs_sparse, the SAH
// sweep, partition_refs) makes for them, found by sorting the records by bin.
// Nodes over 3 to 15 triangles, half of all nodes, cost that path ~2,300
// instructions each, most of them filling and sweeping bins nobody else
// reads; this file takes those up to kSmallNodeMax (wider sizes did not pay).
#include <cstdint>

#include "bvh/records.hpp"
#include "bvh/build_simd.hpp"

namespace clpath::bvh_build {

constexpr std::uint32_t kSmallNodeMax = 8;

struct SmallSplit {
    enum Kind {
        Leaf,   // the node stays a leaf
        Split,  // split at an SAH bin boundary: the fields below are set, dst written
        Other   // neither (no boundary to split at, and too many triangles for a leaf): the binned path decides
    } kind = Other;
    std::uint32_t mid = 0;         // the right child's first record
    Box4 left_box, right_box;      // of the children's triangles
    Box4 left_cbox, right_cbox;    // of their centroids
};

// Records [begin, end) of src, 3 <= end - begin <= kSmallNodeMax, whose
// boxes' union is box and centroids' cbox, with bins per axis. Decides as
// the binned path does (the same costs, the first of equal ones), and for a
// split writes the records to dst as partition_refs does (the left ones in
// order from begin, the right ones in order from end - 1 down), and the
// children's boxes bit for bit as the bins give them. The caller checks the
// depth limit (a forced median split) first.
SmallSplit small_split(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, const Box4& box,
                       const Box4& cbox, int bins, int max_leaf_size, float traversal_cost);

}  // namespace clpath::bvh_build
