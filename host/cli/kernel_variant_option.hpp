#pragma once
// --ab-kernels DIR and --ab-options OPTS, shared by the benchmarks that time a
// variant of the kernels against the built-in ones (bench rays, bench render-ab).
#include <string>

#include <CLI/CLI.hpp>

#include "cl/embedded_sources.hpp"

namespace clpath {

// The kernel files (*.cl, *.h) in dir, by file name, and the options; dir
// empty: options only. Throws clpath::Error for a folder that is missing,
// unreadable or holds no kernel file.
KernelVariant read_kernel_variant(const std::string& dir, const std::string& options);
// The same, with messages naming the option `what` (default "--ab-kernels").
KernelVariant read_kernel_variant(const std::string& dir, const std::string& options, const std::string& what);

// Registers --ab-kernels DIR and --ab-options OPTS on cmd; `kernels` names
// what the variant replaces, `report` what the command prints of it.
void add_kernel_variant_options(CLI::App* cmd, std::string* dir, std::string* options, const std::string& kernels,
                                const std::string& report);

}  // namespace clpath
