#pragma once
// Saving what the viewer shows: the current mean (PNG as displayed, linear
// EXR unscaled, both named with the spp) and the window itself, heads-up
// display included.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/renderer.hpp"

namespace clpath::viewer {

// "cornell-64spp", or "cornell-normals-64spp" for a view other than the path
// tracer: a file name stem that says what the image is.
std::string screenshot_stem(const std::string& scene, const std::string& integrator, std::uint64_t spp);

// Writes DIR/STEM.png (with exposure, as on screen) and DIR/STEM.exr (the
// mean itself; .pfm in a build without OpenImageIO). With a denoised image
// (the viewer's denoising on), DIR/STEM.denoised.png and .exr beside them, as
// render --denoise does: the estimate is always saved, never replaced.
// Creates dir. Returns the paths written.
std::vector<std::string> save_screenshot(Renderer& renderer, const std::string& dir, const std::string& stem,
                                         float exposure, const Image* denoised = nullptr);

// Reads the back buffer (call after drawing, before the swap) into a PNG.
void save_window_capture(const std::string& path, glm::ivec2 framebuffer);

}  // namespace clpath::viewer
