#pragma once
// The two-level BVH of an instanced scene: one bottom-level BVH per mesh
// (build_bvh, widened by widen_bvh, in the mesh's own object space), a
// top-level BVH over the instances' world boxes, and one Instance record per
// instance, flattened into the one node buffer and one triangle buffer the
// kernels read (kernels/shared_structs.h, Instance, says the layout;
// kernels/traverse_instances.cl walks it).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.hpp"

namespace clpath {

struct InstanceInput {
    std::uint32_t mesh = 0;            // index in the meshes given to build_two_level
    glm::mat4 object_to_world{1.0f};   // affine, invertible
};

struct TwoLevelStats {
    std::size_t meshes = 0, instances = 0;
    std::size_t top_nodes = 0;           // 4-wide top-level nodes
    int top_depth = 0;                   // of the 4-wide top level, root = 1
    int bottom_depth = 0;                // of the deepest placed mesh's 4-wide tree
    std::size_t top_bytes = 0;           // top-level nodes and instance records
    std::size_t bottom_bytes = 0;        // bottom-level nodes and their triangles
    double top_build_ms = 0, bottom_build_ms = 0;
    std::size_t placed_triangles = 0;    // every instance's copy counted
};

struct TwoLevelBvh {
    // The top level from node 0, then the instance records, then each mesh's
    // bottom level (child indices and leaf ranges offset into these buffers).
    std::vector<Bvh4Node128> nodes;
    BvhTriangles triangles;  // each mesh's in leaf order; .prim = first_prim[mesh] + its index in the mesh
    std::vector<BvhStats> mesh_stats;  // each bottom level's, as build_bvh gives them
    TwoLevelStats stats;
};

// meshes: each mesh's vertices, three per triangle, object space;
// first_prim: each mesh's first index in the per-triangle buffers (materials,
// normals). Throws clpath::Error for an empty mesh, a mesh index out of range,
// a non-affine, non-finite or singular transform (naming the instance), no
// instances, a top level and deepest placed mesh deeper together than
// CLP_INSTANCE_MAX_DEPTH4 4-wide levels (the walk's stack bound), or more nodes than
// CLP_BVH4_MAX_NODES.
TwoLevelBvh build_two_level(const std::vector<const std::vector<glm::vec3>*>& meshes,
                            const std::vector<std::uint32_t>& first_prim, const std::vector<InstanceInput>& instances,
                            const BvhBuildOptions& options = {});

// The instance's record: the 3x4 rows of object_to_world and of its inverse
// (computed in double), det's sign. Throws clpath::Error (naming `what`) for a
// transform that is not affine, not finite or singular.
Instance instance_record(const glm::mat4& object_to_world, const std::string& what);

// "two-level BVH: 10000 instances of 1 mesh, top level 3.2 MB (2667 nodes, depth 8) built in 4.1 ms, ..."
std::string describe(const TwoLevelStats& stats);

}  // namespace clpath
