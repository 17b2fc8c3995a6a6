#include "cli/kernel_variant_option.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/error.hpp"

namespace clpath {

KernelVariant read_kernel_variant(const std::string& dir, const std::string& options) {
    return read_kernel_variant(dir, options, "--ab-kernels");
}

KernelVariant read_kernel_variant(const std::string& dir, const std::string& options, const std::string& what) {
    KernelVariant v;
    v.options = options;
    if (dir.empty()) return v;
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw Error(what + " " + dir + ": no such folder");
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() || (ext != ".cl" && ext != ".h")) continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        if (!in) throw Error(what + ": cannot read " + e.path().string());
        v.files.emplace_back(e.path().filename().string(), text.str());
    }
    if (ec) throw Error(what + " " + dir + ": " + ec.message());
    if (v.files.empty()) throw Error(what + " " + dir + ": no kernel files (*.cl, *.h) in it");
    std::sort(v.files.begin(), v.files.end());
    return v;
}

void add_kernel_variant_options(CLI::App* cmd, std::string* dir, std::string* options, const std::string& kernels,
                                const std::string& report) {
    cmd->add_option("--ab-kernels", *dir,
                    "A variant of " + kernels + " to time against them: the kernel files (*.cl, *.h) in this folder, each "
                    "replacing clpath's file of that name; launches alternate between the two, and " + report);
    cmd->add_option("--ab-options", *options,
                    "Build options added for the variant's program (alone, or with --ab-kernels), e.g. "
                    "--ab-options=\"-DNAME -cl-denorms-are-zero\"");
}

}  // namespace clpath
