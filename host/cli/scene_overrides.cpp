#include "cli/scene_overrides.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <vector>

#include "image/image.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= s.size(); ++i)
        if (i == s.size() || s[i] == sep) {
            out.push_back(s.substr(start, i - start));
            start = i + 1;
        }
    return out;
}

bool parse_finite(const std::string& t, float& out) {
    const char* b = t.data() + (!t.empty() && t[0] == '+');
    const char* e = t.data() + t.size();
    const auto r = std::from_chars(b, e, out);
    return b != e && r.ptr == e && r.ec == std::errc() && std::isfinite(out) && std::fabs(out) < 1e30f;
}

glm::vec3 parse_vec3(const std::string& option, const std::string& field, const std::string& text) {
    const auto parts = split(text, ',');
    glm::vec3 v;
    if (parts.size() != 3) throw UsageError(option + " " + field + "=" + text + ": expected three numbers x,y,z");
    for (int i = 0; i < 3; ++i)
        if (!parse_finite(parts[std::size_t(i)], v[i]))
            throw UsageError(option + " " + field + "=" + text + ": '" + parts[std::size_t(i)] +
                             "' is not a finite number");
    return v;
}

}  // namespace

Camera apply_camera_option(const std::string& text, Camera cam) {
    const std::string opt = "--camera";
    cam.ortho_half_height = 0;  // --camera gives a perspective camera, also in place of a file's orthographic one
    if (text.empty()) throw UsageError(opt + " is empty; expected from=x,y,z;to=x,y,z;fov=degrees;up=x,y,z;aperture=radius;focus=distance");
    for (const auto& item : split(text, ';')) {
        if (item.empty()) continue;  // a trailing ';'
        const auto eq = item.find('=');
        if (eq == std::string::npos)
            throw UsageError(opt + " '" + item + "': expected NAME=VALUE with NAME one of from, to, fov, up, aperture, focus");
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        if (key == "from") cam.eye = parse_vec3(opt, key, value);
        else if (key == "to") cam.target = parse_vec3(opt, key, value);
        else if (key == "up") cam.up = parse_vec3(opt, key, value);
        else if (key == "fov") {
            float f;
            if (!parse_finite(value, f) || f < 1 || f > 179)
                throw UsageError(opt + " fov=" + value + ": the vertical field of view must be a number of degrees from 1 to 179");
            cam.vfov_degrees = f;
        } else if (key == "aperture") {
            float f;
            if (!parse_finite(value, f) || f < 0)
                throw UsageError(opt + " aperture=" + value + ": the lens radius must be a number >= 0 (0: a pinhole)");
            cam.aperture_radius = f;
        } else if (key == "focus") {
            float f;
            if (!parse_finite(value, f) || !(f > 0))
                throw UsageError(opt + " focus=" + value + ": the focus distance must be a number > 0");
            cam.focus_distance = f;
        } else {
            throw UsageError(opt + " '" + key + "': unknown field (choose from from, to, fov, up, aperture, focus)");
        }
    }
    try {
        (void)camera_data(cam);
    } catch (const Error& e) {
        throw UsageError(opt + " '" + text + "': " + e.what());
    }
    return cam;
}

Environment parse_env_option(const std::string& text) {
    Environment env;
    const auto parts = split(text, ',');
    bool numeric = true;
    glm::vec3 c(0);
    for (std::size_t i = 0; i < parts.size() && i < 3; ++i) numeric = numeric && parse_finite(parts[i], c[int(i)]);
    if (numeric && (parts.size() == 1 || parts.size() == 3)) {
        if (parts.size() == 1) c = glm::vec3(c.x);
        for (int i = 0; i < 3; ++i)
            if (c[i] < 0 || c[i] > 1e6f)
                throw UsageError("--env " + text + ": a colour's channels must be from 0 to 1000000");
        env.color = c;
        return env;
    }
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_regular_file(text, ec)) {
        const bool looks_numeric = text.find_first_not_of("0123456789.,+-eE ") == std::string::npos;
        throw UsageError("--env " + text + ": " +
                         (looks_numeric ? std::string("expected a colour R,G,B or one grey value (finite, from 0 to 1000000)")
                                        : "no such file (give an equirectangular .hdr or .exr image, or a colour R,G,B)"));
    }
    // Not an image (or one with too few channels): bad usage, named now rather than when the render starts.
    try {
        check_image_readable(text);
    } catch (const Error& e) {
        throw UsageError("--env " + text + ": " + e.what());
    }
    env.image = text;
    return env;
}

}  // namespace clpath
