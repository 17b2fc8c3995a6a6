#pragma once
// Polygons with more than three corners (OBJ faces) cut into triangles by ear
// clipping in the polygon's own plane (Newell's normal), so that concave
// polygons are cut inside their outline; a fan would put triangles across a
// notch. Repeated consecutive corners are dropped first, so "f 1 2 2 3" is
// one triangle rather than a degenerate pair.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace clpath {

// Triangles as indices into `corners`, each wound as the polygon is (the
// front face stays the file's). A polygon with fewer than three distinct
// corners, or of zero area, gives the fan of its corners: degenerate
// triangles that the scene builder counts and drops.
std::vector<std::array<std::size_t, 3>> triangulate_polygon(const std::vector<glm::vec3>& corners);

}  // namespace clpath
