#pragma once
// The denoiser's guides for the viewer's current camera: the albedo and
// normals views (render/guides.hpp's definitions, kGuideSamples each, as
// render --denoise makes them), rendered a few samples a frame beside the
// estimate so that a camera move never stalls the window. They use the
// viewer renderer's device scene (no second upload) with films and programs
// of their own, so the estimate's film and kernels are untouched.
#include <cstdint>
#include <memory>

#include "cl/context.hpp"
#include "denoise/denoiser.hpp"
#include "denoise/guides.hpp"
#include "render/film.hpp"
#include "render/integrator_program.hpp"
#include "render/renderer.hpp"

namespace clpath::viewer {

class GuidePasses {
public:
    // Compiles (or loads from the kernel cache) the two views' programs for
    // the renderer's scene and settings. Throws clpath::Error if that fails.
    GuidePasses(Context& ctx, const Renderer& renderer);

    // Starts again for the renderer's current camera (another size: new films).
    void restart(const Renderer& renderer);
    // Adds up to n samples per pixel to the passes; returns how many it added.
    std::uint32_t advance(const Renderer& renderer, std::uint32_t n);
    bool ready() const { return guides_ != nullptr; }
    // Samples per pixel done over both passes, of total().
    std::uint64_t done() const { return albedo_done_ + normals_done_; }
    static constexpr std::uint64_t total() { return 2 * kGuideSamples; }
    // Set once ready(); shared with a denoise in flight, which outlives a restart.
    std::shared_ptr<const DenoiseGuides> guides() const { return guides_; }

private:
    struct Pass {
        std::unique_ptr<IntegratorProgram> program;
        std::unique_ptr<Film> film;
    };
    Image finish(Pass& pass);

    Context& ctx_;
    Pass albedo_, normals_;
    std::uint64_t albedo_done_ = 0, normals_done_ = 0;
    Image albedo_image_;
    std::shared_ptr<const DenoiseGuides> guides_;
};

}  // namespace clpath::viewer
