#pragma once
// The repository's root seen from a test's working folder (build/tests):
// the nearest folder above that holds scenes/hard and benchmarks/references,
// or an empty path (the test then says where it looked).
#include <filesystem>

namespace clpath::test {

inline std::filesystem::path repo_root() {
    namespace fs = std::filesystem;
    for (fs::path p = fs::current_path(); !p.empty(); p = p.parent_path()) {
        if (fs::is_directory(p / "scenes" / "hard") && fs::is_directory(p / "benchmarks" / "references")) return p;
        if (p == p.parent_path()) break;
    }
    return {};
}

}  // namespace clpath::test
