#pragma once
// Where an image goes in a framebuffer of another shape: as large as fits,
// aspect kept, centred. While a window is being resized the old image is
// shown this way until the renderer follows the new size.
#include <algorithm>

#include <glm/glm.hpp>

namespace clpath::viewer {

// (x, y, width, height) in framebuffer pixels.
inline glm::ivec4 letterbox(glm::ivec2 image, glm::ivec2 framebuffer) {
    if (image.x <= 0 || image.y <= 0 || framebuffer.x <= 0 || framebuffer.y <= 0) return {0, 0, 0, 0};
    const double scale = std::min(double(framebuffer.x) / image.x, double(framebuffer.y) / image.y);
    const int w = std::max(1, int(image.x * scale + 0.5)), h = std::max(1, int(image.y * scale + 0.5));
    return {(framebuffer.x - w) / 2, (framebuffer.y - h) / 2, w, h};
}

}  // namespace clpath::viewer
