#pragma once
// The SAH builder's record of a triangle (its box and its index in the
// input), 32 bytes, one 256-bit load, and the pass that makes them.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/build_simd.hpp"

namespace clpath::bvh_build {

struct alignas(16) Ref {
    float lo[3];
    std::uint32_t prim;  // the triangle's index in the input
    float hi[3];
    float pad;
};

// The bounds of all triangles' boxes and of their centroids.
struct RootBounds {
    Box4 box, cbox;
};

// refs[i] for triangle i (vertices 3i .. 3i + 2), on threads threads (fork_join).
// Throws clpath::Error naming the first triangle with a non-finite coordinate.
RootBounds make_records(const std::vector<glm::vec3>& vertices, int threads, Ref* refs);

}  // namespace clpath::bvh_build
