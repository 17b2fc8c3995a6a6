#include "viewer/camera_snippet.hpp"

#include <charconv>

namespace clpath::viewer {
namespace {

std::string number(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string vec(glm::vec3 v) {
    std::string s = "[";
    s.append(number(v.x)).append(", ").append(number(v.y)).append(", ").append(number(v.z)).append("]");
    return s;
}

}  // namespace

std::string camera_snippet(const Camera& c) {
    return "{\"camera\": {\"eye\": " + vec(c.eye) + ", \"target\": " + vec(c.target) + ", \"up\": " + vec(c.up) +
           ", \"vfov\": " + number(c.vfov_degrees) +
           (c.has_lens() ? ", \"aperture_radius\": " + number(c.aperture_radius) +
                               ", \"focus_distance\": " + number(c.resolved_focus_distance())
                         : std::string()) +
           ", \"resolution\": [" + std::to_string(c.width) + ", " +
           std::to_string(c.height) + "]}}";
}

}  // namespace clpath::viewer
