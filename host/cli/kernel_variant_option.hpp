#pragma once
// --ab-kernels DIR and --ab-options OPTS, shared by the benchmarks that time a
// variant of the kernels against the built-in ones (bench rays, bench render-ab).
#include <string>

#include "cl/embedded_sources.hpp"

namespace clpath {

// The kernel files (*.cl, *.h) in dir, by file name, and the options; dir
// empty: options only. Throws clpath::Error for a folder that is missing,
// unreadable or holds no kernel file.
KernelVariant read_kernel_variant(const std::string& dir, const std::string& options);

}  // namespace clpath
