#pragma once
// Rendering whole images in tests, on the test device.
#include <gtest/gtest.h>

#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/scene.hpp"
#include "support/test_device.hpp"

namespace clpath::test {

// The default scene (the thesis renderer's room, all diffuse) at a test's size.
inline Scene small_cornell(int width, int height) {
    Scene s = cornell_thesis_scene();
    s.camera.width = width;
    s.camera.height = height;
    return s;
}

inline RenderedImage render(const Scene& scene, const RenderSettings& settings, std::uint32_t spp,
                            RenderStats* stats = nullptr) {
    Renderer r(device(), scene, settings);
    r.add_samples(spp);
    if (stats) *stats = r.stats();
    return r.resolve();
}

// Per-pixel luminance-free channel means: the image as doubles, one per channel value.
inline std::vector<double> channel(const Image& img, int c) {
    std::vector<double> v(std::size_t(img.width) * img.height);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = img.rgb[i * 3 + c];
    return v;
}

// The integrators that transport light (the others show one quantity: AO, albedo, ...).
inline constexpr std::uint32_t kLightTransportIntegrators[] = {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF};

inline std::size_t nonzero(const Image& img) {
    std::size_t n = 0;
    for (float v : img.rgb) n += v != 0.0f;
    return n;
}

// Renders, and expects no non-finite sample and every value of the image to
// be exactly `value` (an exact answer: open AO, a dark room, a constant emitter).
inline void expect_every_value(const Scene& scene, const RenderSettings& settings, std::uint32_t spp, float value) {
    RenderStats stats;
    const Image img = render(scene, settings, spp, &stats).linear;
    EXPECT_EQ(stats.nonfinite, 0u) << integrator_name(settings.integrator);
    std::size_t other = 0, first = 0;
    for (std::size_t i = img.rgb.size(); i-- > 0;)
        if (img.rgb[i] != value) ++other, first = i;
    EXPECT_EQ(other, 0u) << integrator_name(settings.integrator) << ": of " << img.rgb.size() << " values, "
                         << other << " are not " << value << "; the first, value " << first << ", is "
                         << (other ? img.rgb[first] : value);
}

}  // namespace clpath::test
