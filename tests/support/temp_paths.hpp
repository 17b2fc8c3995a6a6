#pragma once
// Paths for a test's scratch files in the system's temporary folder. The
// process id is in the name: the same test program may run twice at once (two
// build folders, or two checkouts, testing on one machine), and two runs that
// wrote one file would read each other's.
#include <filesystem>
#include <string>

#include <unistd.h>

namespace clpath::test {

inline std::string temp_path(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("clpath-" + std::to_string(::getpid()) + "-" + name)).string();
}

}  // namespace clpath::test
