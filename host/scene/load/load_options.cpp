#include "scene/load/load_options.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/error.hpp"

namespace clpath {

namespace {
std::filesystem::path& allowed_root() {
    static std::filesystem::path root;
    return root;
}
}  // namespace

void restrict_files_to(const std::string& dir) {
    namespace fs = std::filesystem;
    if (dir.empty()) {
        allowed_root().clear();
        return;
    }
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw UsageError("--restrict-files " + dir + ": not a folder");
    allowed_root() = fs::canonical(dir, ec);
    if (ec) throw UsageError("--restrict-files " + dir + ": " + ec.message());
}

void check_file_allowed(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path& root = allowed_root();
    if (root.empty()) return;
    std::error_code ec;
    // Symbolic links in the part that exists are followed; "..", "." removed.
    fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) resolved = fs::absolute(path).lexically_normal();
    auto r = root.begin();
    for (auto p = resolved.begin(); r != root.end(); ++r, ++p)
        if (p == resolved.end() || *p != *r)
            throw RestrictedFileError(path + ": resolves to " + resolved.string() + ", outside " + root.string() +
                        ", the folder --restrict-files allows");
}

std::string read_text_file(const std::string& path) {
    namespace fs = std::filesystem;
    check_file_allowed(path);
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    // Checked first: reading a folder or a device (/dev/zero) would fail late or never end.
    if (!fs::exists(st)) throw Error(path + ": no such file");
    if (fs::is_directory(st)) throw Error(path + ": is a folder, not a file");
    if (!fs::is_regular_file(st)) throw Error(path + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot be read (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw Error(path + ": read failed (" + std::strerror(errno) + ")");
    return std::move(s).str();
}

}  // namespace clpath
