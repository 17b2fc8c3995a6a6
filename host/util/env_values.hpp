#pragma once
// Environment variables that hold numbers are read strictly: a value that is
// not what the variable takes is a clpath::UsageError naming the variable and
// what it accepts, never silently read as 0.
#include <cstdint>
#include <optional>
#include <string>

namespace clpath {

// A whole number in [lo, hi] from $name; nullopt when it is unset or empty.
std::optional<std::uint64_t> env_whole_number(const char* name, std::uint64_t lo, std::uint64_t hi,
                                              const std::string& unit);

}  // namespace clpath
