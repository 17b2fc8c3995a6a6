#pragma once
// Independent runs of one scene for the statistical tests, and the scene
// placed elsewhere (moved, scaled) for the scale-invariance tests.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "image/image.hpp"
#include "render/render_session.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"
#include "support/test_device.hpp"

namespace clpath::test {

// K renders with seeds seed0, seed0 + 1, ..., from one Renderer (kernels and
// BVH built once); the non-finite samples of all runs are added to *nonfinite.
// With CLPATH_TEST_NOISE_TARGET=R in the environment (the adaptive.* reruns
// of the agreement tests, tests/CMakeLists.txt), each run is an adaptive
// render to the noise target R of at most 4 x spp samples (render_session on
// the test device; 4 x so that pixels can stop before the cap, the tests'
// counts being as low as 16), so the agreement tests check that adaptive
// sampling leaves the estimate unbiased. The share of samples it saved is
// printed, to show that pixels did stop.
inline std::vector<Image> render_runs(const Scene& scene, RenderSettings st, std::uint32_t spp, int k,
                                      std::uint32_t seed0, std::uint64_t* nonfinite = nullptr) {
    std::vector<Image> out;
    if (const char* target = std::getenv("CLPATH_TEST_NOISE_TARGET"); target && *target) {
        SessionOptions so;
        so.spp = 4ull * spp;
        so.noise_target = std::stod(target);
        double taken = 0, cap = 0;
        for (int i = 0; i < k; ++i) {
            st.seed = seed0 + std::uint32_t(i);
            const SessionResult r = render_session(scene, st, {device().device()}, so);
            if (nonfinite) *nonfinite += r.nonfinite;
            for (std::size_t p = 0; p < r.film.pixel_samples().size(); ++p) taken += double(r.film.samples_of(p));
            cap += double(so.spp) * double(r.film.pixel_samples().size());
            out.push_back(r.film.mean());
        }
        std::fprintf(stderr, "[ adaptive ] noise target %s: %.1f%% of the %llu-spp cap taken\n", target,
                     100.0 * taken / cap, (unsigned long long)so.spp);
        return out;
    }
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
    // Instances: the same meshes, placed by the map composed after theirs.
    const glm::dmat4 world = glm::translate(glm::dmat4(1.0), offset) * glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
    for (auto& in : out.instances) in.object_to_world = glm::mat4(world * glm::dmat4(in.object_to_world));
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
