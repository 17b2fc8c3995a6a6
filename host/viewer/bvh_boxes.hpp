#pragma once
// The boxes of a flattened BVH down to a depth, for the overlay. Level 1 is
// the root's two child boxes (the Aila-Laine layout stores a node's children's
// boxes, not its own), level 2 their children's, and so on.
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.hpp"
#include "shared_structs.h"

namespace clpath::viewer {

struct LevelBox {
    glm::vec3 lo, hi;
    int level;
};

// Every box of level 1..max_level; leaves end their branch early.
std::vector<LevelBox> bvh_boxes(const BvhNodes& nodes, int max_level);

// The deepest level that has a box: how far the overlay's depth can go.
int bvh_levels(const BvhNodes& nodes);

// The 24 endpoints of a box's 12 edges, as line-list vertices.
std::vector<glm::vec3> box_edges(const LevelBox& box);

}  // namespace clpath::viewer
