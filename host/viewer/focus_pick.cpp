#include "viewer/focus_pick.hpp"

#include <cmath>
#include <limits>

namespace clpath::viewer {

std::optional<float> focus_distance_at(const std::vector<glm::vec3>& tris, const Camera& camera, glm::vec2 pixel) {
    const CameraData cd = camera_data(camera);
    const glm::dvec3 eye(camera.eye), fwd(cd.forward[0], cd.forward[1], cd.forward[2]);
    const glm::dvec3 right(cd.right[0], cd.right[1], cd.right[2]), up(cd.up[0], cd.up[1], cd.up[2]);
    // kernels/camera.cl's pinhole mapping, at this point of the image.
    const double x = 2.0 * double(pixel.x) / double(cd.width) - 1.0;
    const double y = 1.0 - 2.0 * double(pixel.y) / double(cd.height);
    const glm::dvec3 d = glm::normalize(fwd + x * right + y * up);
    double best = std::numeric_limits<double>::infinity();
    // Moeller & Trumbore (1997), both faces.
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
        const glm::dvec3 a(tris[i]), e1 = glm::dvec3(tris[i + 1]) - a, e2 = glm::dvec3(tris[i + 2]) - a;
        const glm::dvec3 p = glm::cross(d, e2);
        const double det = glm::dot(e1, p);
        if (det == 0.0 || !std::isfinite(det)) continue;
        const double inv = 1.0 / det;
        const glm::dvec3 s = eye - a;
        const double u = glm::dot(s, p) * inv;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(d, q) * inv;
        if (v < 0.0 || u + v > 1.0) continue;
        const double t = glm::dot(e2, q) * inv;
        if (t > 0.0 && t < best) best = t;
    }
    if (!std::isfinite(best)) return std::nullopt;
    const double along = best * glm::dot(d, fwd);
    if (!(along > 0.0)) return std::nullopt;
    return float(along);
}

std::optional<glm::vec2> window_to_image(glm::vec2 window, glm::vec2 scale, glm::ivec2 framebuffer, glm::ivec4 rect,
                                         glm::ivec2 image) {
    if (rect.z <= 0 || rect.w <= 0 || image.x <= 0 || image.y <= 0) return std::nullopt;
    const glm::vec2 fb = window * scale;
    const float top = float(framebuffer.y - (rect.y + rect.w));  // the rect's top row, y down
    const glm::vec2 in((fb.x - float(rect.x)) / float(rect.z), (fb.y - top) / float(rect.w));
    if (in.x < 0 || in.y < 0 || in.x >= 1 || in.y >= 1) return std::nullopt;
    return in * glm::vec2(image);
}

}  // namespace clpath::viewer
