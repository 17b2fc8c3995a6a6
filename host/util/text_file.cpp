#include "util/text_file.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "util/error.hpp"

namespace clpath {

void check_text_output_path(const std::string& path) {
    namespace fs = std::filesystem;
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw Error("output " + path + ": folder " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error("output " + path + ": folder " + dir.string() + " is not writable");
    if (fs::is_directory(path, ec)) throw Error("output " + path + ": is a folder");
}

void write_text_file(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw Error(path + ": cannot write (does the folder exist?)");
    const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const bool closed = std::fclose(f) == 0;
    std::error_code ec;
    if (!written || !closed) {
        std::filesystem::remove(tmp, ec);
        throw Error(path + ": write failed (disk full?)");
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error(path + ": cannot replace: " + ec.message());
    }
}

}  // namespace clpath
