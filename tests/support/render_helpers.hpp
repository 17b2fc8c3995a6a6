#pragma once
// Rendering whole images in tests, on the test device.
#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"
#include "support/test_device.hpp"

namespace clpath::test {

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

}  // namespace clpath::test
