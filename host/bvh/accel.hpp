#pragma once
// Which acceleration structure the kernels traverse: the SAH BVH (bvh.hpp),
// or the thesis renderer's flat list of one box per object (flat.hpp), kept
// as the baseline the BVH is measured against. Both come out as a Bvh record
// (nodes + leaf-ordered triangles), so buffers, kernels and the integrator
// are the same; only the traversal differs (-DCLP_ACCEL_FLAT, kernels/traverse.cl).
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/bvh.hpp"

namespace clpath {

enum class Accel { Bvh, Flat };

// "bvh", "flat"; parse_accel throws clpath::Error naming the choices.
const std::vector<std::string>& accel_names();
Accel parse_accel(const std::string& name);
const char* accel_name(Accel accel);

// The structure for a scene's triangles. triangle_object (one per triangle)
// is read only by the flat structure.
Bvh build_accel(Accel accel, const std::vector<glm::vec3>& vertices,
                const std::vector<std::uint32_t>& triangle_object, const BvhBuildOptions& options = {});

// How many children a BVH node holds on the device: four (Bvh4Node128, what
// GPUs and instanced scenes walk) or eight (Bvh8Node256, what CPUs walk).
// The program that walks the nodes is built for the same layout
// (render/kernel_programs.hpp, node_layout and layout_options).
enum class NodeLayout { Bvh4, Bvh8 };

// The node buffer the kernels traverse (kernels/traverse*.cl, AccelNode), as
// bytes: the BVH widened to the layout's children per node (bvh/wide.hpp),
// or the flat list's records as built (the layout then says nothing).
std::vector<unsigned char> device_nodes(Accel accel, const Bvh& structure, NodeLayout layout);

}  // namespace clpath
