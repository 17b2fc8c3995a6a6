#pragma once
// The convergence benchmark's measurement: render a scene progressively with
// one estimator configuration and record, at 1, 2, 4, ... samples per pixel,
// the render time and the error against a reference image.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "image/compare.hpp"
#include "image/image.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct ConvergencePoint {
    std::uint64_t spp = 0;
    double seconds = 0;  // render time to this point (launches only: no resolve, no comparison)
    ImageComparison error;
};

struct ConvergenceLimits {
    std::uint64_t max_spp = 1024;  // the last power of two measured is at most this
    // Stop before a doubling that would, at the speed so far, end past this
    // many seconds of render time (0: no cap).
    double time_cap = 0;
};

// Renders scene (at its camera's resolution, which the reference must equal)
// with settings. A warm-up sample is rendered and discarded first, so that
// the times leave out the device's first-launch work. on_point sees each
// point as it is measured.
std::vector<ConvergencePoint> measure_convergence(Context& ctx, const Scene& scene, const RenderSettings& settings,
                                                  const Image& reference, const CompareOptions& compare,
                                                  const ConvergenceLimits& limits,
                                                  const std::function<void(const ConvergencePoint&)>& on_point = {});

// The reference at a k times smaller resolution (k an integer): the mean of
// each k x k block. With a box pixel filter this is exactly the image a
// k times smaller render converges to, so one committed reference serves
// every size that divides it. Throws clpath::Error naming `what` when the
// sizes are not such a multiple.
Image reference_at(const Image& reference, int width, int height, const std::string& what);

}  // namespace clpath
