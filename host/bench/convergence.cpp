#include "bench/convergence.hpp"

#include <chrono>
#include <cmath>

#include "render/renderer.hpp"
#include "util/error.hpp"

namespace clpath {

std::vector<ConvergencePoint> measure_convergence(Context& ctx, const Scene& scene, const RenderSettings& settings,
                                                  const Image& reference, const CompareOptions& compare,
                                                  const ConvergenceLimits& limits,
                                                  const std::function<void(const ConvergencePoint&)>& on_point) {
    if (reference.width != scene.camera.width || reference.height != scene.camera.height)
        throw Error("internal: reference and render sizes differ");
    Renderer renderer(ctx, scene, settings);
    // The first launch sizes the later ones and, on some drivers, finishes
    // compiling the kernel for its work-group size: not part of convergence.
    renderer.add_samples(1);
    renderer.reset();

    std::vector<ConvergencePoint> points;
    double seconds = 0;
    for (std::uint64_t spp = 1; spp <= limits.max_spp; spp *= 2) {
        const std::uint64_t done = renderer.stats().samples_per_pixel;
        // Each doubling costs about as much as everything before it.
        if (limits.time_cap > 0 && done > 0 && seconds * double(spp - done) / double(done) + seconds > limits.time_cap)
            break;
        const auto t0 = std::chrono::steady_clock::now();
        renderer.add_samples(std::uint32_t(spp - done));  // returns when the launches have finished
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ConvergencePoint p;
        p.spp = spp;
        p.seconds = seconds;
        p.error = compare_images(renderer.resolve().linear, reference, compare);
        if (renderer.stats().nonfinite)
            throw Error("configuration produced " + std::to_string(renderer.stats().nonfinite) +
                        " NaN or infinite samples");
        points.push_back(p);
        if (on_point) on_point(p);
    }
    return points;
}

Image reference_at(const Image& ref, int width, int height, const std::string& what) {
    if (ref.width == width && ref.height == height) return ref;
    const int k = width > 0 ? ref.width / width : 0;
    if (k < 1 || ref.width != k * width || ref.height != k * height)
        throw Error(what + ": reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                    ", which is not the render size " + std::to_string(width) + "x" + std::to_string(height) +
                    " or an integer multiple of it");
    Image out;
    out.width = width;
    out.height = height;
    out.rgb.assign(std::size_t(width) * height * 3, 0.0f);
    const double inv = 1.0 / (double(k) * k);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int j = 0; j < k; ++j)
                    for (int i = 0; i < k; ++i) sum += ref.at(x * k + i, y * k + j, c);
                out.rgb[(std::size_t(y) * width + x) * 3 + c] = float(sum * inv);
            }
    return out;
}

}  // namespace clpath
