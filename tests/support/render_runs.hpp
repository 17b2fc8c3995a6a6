#pragma once
// Independent runs of one scene for the statistical tests, and the scene
// placed elsewhere (moved, scaled) for the scale-invariance tests.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"
#include "support/test_device.hpp"

namespace clpath::test {

// K renders with seeds seed0, seed0 + 1, ..., from one Renderer (kernels and
// BVH built once); the non-finite samples of all runs are added to *nonfinite.
inline std::vector<Image> render_runs(const Scene& scene, RenderSettings st, std::uint32_t spp, int k,
                                      std::uint32_t seed0, std::uint64_t* nonfinite = nullptr) {
    std::vector<Image> out;
    Renderer r(device(), scene, st);
    for (int i = 0; i < k; ++i) {
        st.seed = seed0 + std::uint32_t(i);
        r.set_settings(st);
        r.add_samples(spp);
        if (nonfinite) *nonfinite += r.stats().nonfinite;
        out.push_back(r.resolve().linear);
    }
    return out;
}

// The scene under x -> scale * x + offset: vertices, camera, punctual lights
// (point and spot intensities times scale^2, so the irradiance they give at
// the scaled distances is unchanged) and the ambient occlusion distance. The
// image is invariant in exact arithmetic; computed in double and rounded once.
inline Scene placed(const Scene& s, double scale, glm::dvec3 offset) {
    Scene out = s;
    auto move = [&](glm::vec3 p) { return glm::vec3(glm::dvec3(p) * scale + offset); };
    for (auto& v : out.vertices) v = move(v);
    out.camera.eye = move(s.camera.eye);
    out.camera.target = move(s.camera.target);
    for (auto& l : out.lights) {
        l.position = move(l.position);
        if (l.type != PunctualLight::Type::Directional) l.intensity *= float(scale * scale);
    }
    out.render.ao_distance = float(double(s.render.ao_distance) * scale);
    return out;
}

}  // namespace clpath::test
