#pragma once
// Random triangle soups and rays for the traversal and BVH tests: one
// generator each, so every structure is tested on the same kind of input.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace clpath::test {

// n triangles (3 vertices each), centres uniform in [-1, 1]^3, each vertex
// within size s of its centre, s uniform in [min_size, max_size] per triangle.
std::vector<glm::vec3> random_soup(std::size_t n, std::uint32_t seed, float min_size, float max_size);

struct TestRay {
    glm::vec3 o, d;  // d is unit length
};

// Origins uniform in [-1.5, 1.5]^3. Odd rays aim at a random point of a random
// triangle of mesh, so every mesh, however small, sees hits; the others go
// anywhere; every seventh is axis-aligned with signed zeros, where slab tests
// are fragile.
std::vector<TestRay> random_rays(std::size_t n, std::uint32_t seed, const std::vector<glm::vec3>& mesh);

// The rays as 6 floats each (origin, direction), as the traversal probes take them.
std::vector<float> packed(const std::vector<TestRay>& rays);

}  // namespace clpath::test
