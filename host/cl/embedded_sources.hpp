#pragma once
// Kernel sources compiled into the binary by cmake/embed_sources.cmake, so that
// clpath runs from any directory.
#include <string>
#include <vector>

namespace clpath {

struct EmbeddedSource {
    const char* name;  // file name, e.g. "rng.cl"
    const char* text;
};

const std::vector<EmbeddedSource>& embedded_sources();

// The text of one embedded file; throws if there is none of that name.
const std::string& embedded_source(const std::string& name);

// An OpenCL program is the shared struct header followed by the named kernel
// files in order (the .cl files have no #include: order here is their dependency order).
std::string program_source(const std::vector<std::string>& files);

// The renderer's kernel files, in dependency order.
const std::vector<std::string>& renderer_kernel_files();

}  // namespace clpath
