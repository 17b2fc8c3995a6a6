#pragma once
// Scenes whose images are known in closed form, for the tests that check
// light transport against them, and the integer room, whose image must not
// change when it is moved or scaled.
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath::test {

// White furnace: the camera at the centre of a closed sphere (icosphere 3)
// whose inside has albedo a and emits Le (two-sided). Every path gathers
// Le (1 + a + a^2 + ...): see furnace_radiance. The caller sets the film size.
Scene furnace_sphere(glm::vec3 albedo, glm::vec3 le);
// The furnace's expected radiance for paths of at most `bounces` bounces:
// Le (1 - a^(bounces+1)) / (1 - a).
double furnace_radiance(double le, double albedo, int bounces);

// A floor (the plane y = 0, 100 x 100 about the origin) and a wall standing
// on it in the plane x = 0, facing +x, both of `material`. No camera.
void add_floor_and_wall(Scene& s, std::uint32_t material);

// Ambient occlusion with rays of length d on the floor at distance x from the
// wall: 1 - blocked(x / d), blocked(c) = (acos c - c sqrt(1 - c^2)) / pi.
// Malley's method: cosine-weighted directions project uniformly onto the unit
// disk, and those that reach the wall within d are the disk's segment beyond c.
double ao_next_to_wall(double x, double d);

// A furnace under a constant sky (s.environment.color): objects that conserve
// energy, so that every pixel's expectation is factor x the sky. Renders 64
// samples of paths up to 64 bounces with the given integrator and seed, and
// expects no non-finite sample and each channel's image mean within 3.89
// standard errors (alpha 1e-4 per channel; pixels are independent estimates)
// plus float rounding along the path (gamma(4) per bounce: 256 u).
void expect_sky_furnace(const Scene& s, double factor, std::uint32_t integrator, std::uint32_t seed);

// The integer room: a closed 128-unit box lit by a two-sided square lamp
// (radiance 12) under its ceiling; two boxes standing on the floor, one
// touching the back wall and one in a corner (contact lines where leaks show),
// all on integer coordinates, the camera inside (32 x 32). No environment.
Scene integer_room();

}  // namespace clpath::test
