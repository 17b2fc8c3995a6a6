#pragma once
// Shape generators, as in the thesis renderer: each builds a shape in a unit
// local frame with outward-facing triangles (3 vertices each), and
// transformed() places it. Parameters out of range throw clpath::Error.
#include <cstddef>
#include <utility>
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

// A triangle soup with a smooth shading normal at every corner (3 of each per triangle).
struct ShapeMesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::vec3> normals;
    std::size_t triangle_count() const { return vertices.size() / 3; }
};

// A bumpy surface, so that a tessellated shape is not a flat-faced copy of a
// coarse one: the BVH of the scaling benchmark then has real work at every level.
struct Bumps {
    enum class Kind { None, Sine, Ripple };
    Kind kind = Kind::None;
    float amplitude = 0;  // in the shape's local units (unit sphere, unit grid)
    float frequency = 1;  // waves per local unit
};

// Rings (latitude bands) and segments of the UV sphere closest to a requested
// triangle count, which is 2 * segments * (rings - 1).
std::pair<int, int> uv_sphere_resolution(std::size_t triangles);
// The unit UV sphere of about `triangles` triangles (at least 12), poles on y,
// outward facing. Bumps of kind Sine move each vertex along its normal by
// amplitude * sin(2 pi f x) sin(2 pi f y) sin(2 pi f z); Ripple by
// amplitude * cos(2 pi f y).
ShapeMesh make_uv_sphere(std::size_t triangles, const Bumps& bumps = {});
// The unit grid in the xz-plane (like make_plane) of nx * nz cells, two
// triangles each, facing +y, raised by a height function: Sine:
// amplitude * sin(2 pi f x) sin(2 pi f z); Ripple: amplitude * cos(2 pi f r),
// r the distance from the centre.
ShapeMesh make_grid(int nx, int nz, const Bumps& height = {});
// The icosphere with its exact sphere normals.
ShapeMesh make_smooth_icosphere(int iterations);

// translate(position) * rotX(r.x) * rotY(r.y) * rotZ(r.z) * scale(s), angles in
// radians: the thesis renderer's transform order.
glm::mat4 shape_transform(glm::vec3 position, glm::vec3 rotation, glm::vec3 scale);

// Applies m to every vertex. A mirroring m (negative determinant) would turn
// triangles inside out, so their winding is swapped to keep them facing out.
std::vector<glm::vec3> transformed(const std::vector<glm::vec3>& tris, const glm::mat4& m);

}  // namespace clpath
