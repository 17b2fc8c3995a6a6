#include "support/random_geometry.hpp"

#include <random>

namespace clpath::test {

std::vector<glm::vec3> random_soup(std::size_t n, std::uint32_t seed, float min_size, float max_size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1, 1), size(min_size, max_size);
    std::vector<glm::vec3> v;
    v.reserve(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        const float s = size(rng);
        for (int k = 0; k < 3; ++k) v.push_back(c + s * glm::vec3(pos(rng), pos(rng), pos(rng)));
    }
    return v;
}

std::vector<TestRay> random_rays(std::size_t n, std::uint32_t seed, const std::vector<glm::vec3>& mesh) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.5f, 1.5f), dir(-1, 1), unit(0, 1);
    std::uniform_int_distribution<std::size_t> pick(0, mesh.size() / 3 - 1);
    std::vector<TestRay> rays(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 o(pos(rng), pos(rng), pos(rng));
        glm::vec3 d(dir(rng), dir(rng), dir(rng));
        if (i % 2) {
            const std::size_t t = pick(rng);
            float a = unit(rng), b = unit(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            d = mesh[3 * t] + a * (mesh[3 * t + 1] - mesh[3 * t]) + b * (mesh[3 * t + 2] - mesh[3 * t]) - o;
        }
        if (i % 7 == 0) d = glm::vec3(i % 2 ? -0.0f : 0.0f, 0.0f, dir(rng) < 0 ? -1.0f : 1.0f);
        rays[i] = {o, glm::normalize(d)};
    }
    return rays;
}

std::vector<float> packed(const std::vector<TestRay>& rays) {
    std::vector<float> r;
    r.reserve(6 * rays.size());
    for (const TestRay& ray : rays) {
        for (int k = 0; k < 3; ++k) r.push_back(ray.o[k]);
        for (int k = 0; k < 3; ++k) r.push_back(ray.d[k]);
    }
    return r;
}

}  // namespace clpath::test
