#include "scene/load/obj_tokens.hpp"

#include <charconv>
#include <cmath>

namespace clpath::obj_text {

std::string name_of(std::string_view rest) {
    std::size_t i = 0, j = rest.size();
    while (i < j && is_space(rest[i])) ++i;
    while (j > i && is_space(rest[j - 1])) --j;
    return std::string(rest.substr(i, j - i));
}

std::string with_slashes(std::string path) {
    for (auto& c : path)
        if (c == '\\') c = '/';
    return path;
}

bool parse_double(std::string_view t, double& out) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
    if (r.ptr != t.data() + t.size()) return false;
    if (r.ec == std::errc::result_out_of_range) out = HUGE_VAL;
    return r.ec == std::errc() || r.ec == std::errc::result_out_of_range;
}

std::size_t parse_leading_double(std::string_view t, double& out) {
    const std::size_t sign = !t.empty() && t[0] == '+' ? 1 : 0;
    const auto r = std::from_chars(t.data() + sign, t.data() + t.size(), out);
    if (r.ptr == t.data() + sign) return 0;
    if (r.ec == std::errc::result_out_of_range) out = HUGE_VAL;  // said so by the caller, as in parse_double
    else if (r.ec != std::errc()) return 0;
    return std::size_t(r.ptr - t.data());
}

bool parse_int(std::string_view t, long long& out) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    if (t.empty()) return false;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

}  // namespace clpath::obj_text
