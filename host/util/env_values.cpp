#include "util/env_values.hpp"

#include <charconv>
#include <cstdlib>

#include "util/error.hpp"

namespace clpath {

std::optional<std::uint64_t> env_whole_number(const char* name, std::uint64_t lo, std::uint64_t hi,
                                              const std::string& unit) {
    const char* env = std::getenv(name);
    if (!env || !*env) return std::nullopt;
    const std::string s = env;
    std::uint64_t v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || v < lo || v > hi)
        throw UsageError(std::string(name) + "='" + s + "': expected a whole number of " + unit + " from " +
                         std::to_string(lo) + " to " + std::to_string(hi));
    return v;
}

}  // namespace clpath
