#include "cli/checkpoint_options.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "util/error.hpp"

namespace clpath {

void check_checkpoint_destination(const std::string& path, bool named) {
    namespace fs = std::filesystem;
    const std::string option = named ? "--checkpoint-file " + path : "--checkpoint: the checkpoint file " + path;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw UsageError(option + ": is a folder (name a file in it)");
    const fs::path folder = fs::path(path).parent_path();
    const std::string shown = folder.empty() ? std::string(".") : folder.string();
    if (!folder.empty() && !fs::is_directory(folder, ec))
        throw UsageError(option + ": folder " + shown + " does not exist");
    // Created and removed at once: the writer's own temporary name, so nothing else is touched.
    const std::string probe = path + ".tmp";
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) throw UsageError(option + ": cannot write in folder " + shown + " (" + std::strerror(errno) + ")");
    std::fclose(f);
    std::remove(probe.c_str());
}

void check_resume_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw UsageError("--resume " + path + ": no such file");
    if (!fs::is_regular_file(st)) throw UsageError("--resume " + path + ": not a regular file (name a checkpoint file)");
}

}  // namespace clpath
