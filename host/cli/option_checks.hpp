#pragma once
// Checks for numeric options that say what they accept in plain numbers.
// CLI11 runs them on the text before converting it, so they also catch what
// its conversions let through or report vaguely: nan, inf, -1 for an
// unsigned option, numbers past the type's range.
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace clpath {

// "12.5", "0.001", "1000000": a number as a person writes it, no exponent.
std::string plain_number(double v);

// A whole number from lo to hi, written in decimal digits.
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi);

// A finite number in [lo, hi], or (lo, hi] when lo_open.
CLI::Validator real_number(double lo, double hi, bool lo_open = false);

// Text that must not be empty: an empty --device '' would otherwise mean "the
// default", silently. `what` says what to give instead.
CLI::Validator non_empty(const std::string& what);
inline const char* const kDeviceChoices = "a device index or name, cpu, gpu or all (see 'clpath devices')";

// The help of every command's scene argument: each loads what render loads.
std::string scene_argument_help();

}  // namespace clpath
