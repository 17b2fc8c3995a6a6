#pragma once
// The thesis renderer's acceleration structure (trac0r, 2016): one bounding
// box per object, and a ray that enters a box tests every triangle inside it.
// Stored in BvhNode64 records so the kernels read it through the same buffers:
// each record holds two objects as leaf slots (child = ~first triangle,
// count = the object's triangles); the list ends at the first slot whose
// child is not a leaf (>= 0). kernels/traverse_flat.cl walks it when built with
// -DCLP_ACCEL_FLAT.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.hpp"

namespace clpath {

// vertices: three per triangle; triangle_object: one object id per triangle
// (Scene::triangle_object). Triangles are grouped by object, in order of
// first appearance. Stats: node_count = records, leaf_count = objects,
// sah_cost = every record visited by every ray that enters the scene
// (traversal_cost each) plus each object's triangles weighted by its box's
// area, normalised like the BVH's. Throws clpath::Error for no triangles or
// mismatched sizes.
Bvh build_flat(const std::vector<glm::vec3>& vertices, const std::vector<std::uint32_t>& triangle_object,
               float traversal_cost = 1.0f);

// Throws std::logic_error naming the first broken invariant: every triangle
// once, inside its object's box, the list terminated.
void check_flat(const Bvh& flat, std::size_t triangle_count);

}  // namespace clpath
