#pragma once
// Shape generators, as in the thesis renderer: each builds a shape in a unit
// local frame with outward-facing triangles (3 vertices each), and
// transformed() places it.
#include <vector>

#include <glm/glm.hpp>

namespace clpath {

// The unit square in the local xz-plane, corners (+-0.5, 0, +-0.5), facing +y.
std::vector<glm::vec3> make_plane();
// The unit cube, corners (+-0.5, +-0.5, +-0.5), 12 triangles facing outward.
std::vector<glm::vec3> make_box();
// The unit icosahedron, each triangle split into four `iterations` times,
// vertices on the unit sphere: 20 * 4^iterations triangles.
std::vector<glm::vec3> make_icosphere(int iterations);

// translate(position) * rotX(r.x) * rotY(r.y) * rotZ(r.z) * scale(s), angles in
// radians: the thesis renderer's transform order.
glm::mat4 shape_transform(glm::vec3 position, glm::vec3 rotation, glm::vec3 scale);

// Applies m to every vertex. A mirroring m (negative determinant) would turn
// triangles inside out, so their winding is swapped to keep them facing out.
std::vector<glm::vec3> transformed(const std::vector<glm::vec3>& tris, const glm::mat4& m);

}  // namespace clpath
