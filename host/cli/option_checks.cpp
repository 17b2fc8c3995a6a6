#include "cli/option_checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "scene/builtin_scenes.hpp"

namespace clpath {

std::string scene_argument_help() {
    std::string names;
    for (const auto& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    return "Scene file (.json), mesh (.obj), glTF model (.gltf, .glb) or built-in scene (" + names + ")";
}

std::string plain_number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", v);
    std::string s = buf;
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

CLI::Validator non_empty(const std::string& what) {
    return CLI::Validator(
        [what](std::string& text) -> std::string { return text.empty() ? "an empty value; give " + what : std::string(); },
        "TEXT");
}

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
    const std::string range = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            std::uint64_t v = 0;
            const char* end = text.data() + text.size();
            const auto r = std::from_chars(text.data(), end, v);
            if (text.empty() || r.ptr != end || r.ec != std::errc() || v < lo || v > hi)
                return "'" + text + "' is not " + range;
            return {};
        },
        "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

CLI::Validator real_number(double lo, double hi, bool lo_open) {
    const std::string range = std::string("a finite number ") + (lo_open ? "above " : "from ") + plain_number(lo) +
                              (lo_open ? " and up to " : " to ") + plain_number(hi);
    return CLI::Validator(
        [lo, hi, lo_open, range](std::string& text) -> std::string {
            double v = 0;
            const char* begin = text.data() + (!text.empty() && text[0] == '+');
            const char* end = text.data() + text.size();
            const auto r = std::from_chars(begin, end, v);
            const bool ok = begin != end && r.ptr == end && r.ec == std::errc() && std::isfinite(v) &&
                            (lo_open ? v > lo : v >= lo) && v <= hi;
            if (!ok) return "'" + text + "' is not " + range;
            return {};
        },
        std::string("NUMBER in ") + (lo_open ? "(" : "[") + plain_number(lo) + ", " + plain_number(hi) + "]");
}

}  // namespace clpath
