#pragma once
// Kernel sources compiled into the binary by cmake/embed_sources.cmake, so that
// clpath runs from any directory, and the one function that assembles them
// into a program.
#include <string>
#include <utility>
#include <vector>

namespace clpath {

struct EmbeddedSource {
    const char* name;  // file name, e.g. "rng.cl"
    const char* text;
};
using SourceTable = std::vector<EmbeddedSource>;

// kernels/*.cl and kernels/*.h.
const SourceTable& embedded_sources();

// The text of one file of embedded_sources(); throws if there is none of that name.
const std::string& embedded_source(const std::string& name);

// The source of an OpenCL program: the root files in order, each with the
// files it #includes ("name", looked up in embedded_sources() and in
// `extra`, whose names must differ from those) put in place of the #include line, and each file taken
// once (as #pragma once would; the files also have include guards). Includes
// are resolved here rather than by the OpenCL compiler because the files
// exist only inside the binary, and a driver cannot be shown them portably.
// A quoted #include must therefore be unconditional; <...> includes are left
// alone (shared_structs.h has one for the host, in a branch OpenCL skips).
// #line directives keep compiler messages pointing at the right file and line.
// Throws clpath::Error for a file that is not embedded.
std::string program_source(const std::vector<std::string>& roots, const SourceTable& extra = {});

// A variant of the kernels, to be timed against the built-in ones (bench rays
// and bench render-ab): kernel files replacing embedded ones of the same
// names, and build options added to those the program is built with.
struct KernelVariant {
    std::vector<std::pair<std::string, std::string>> files;  // (file name, text)
    std::string options;
    bool empty() const { return files.empty() && options.empty(); }
};

// The variant's program: program_source with the variant's files in place of
// the embedded ones of the same names (clpath::Error naming a file that
// replaces none), and the built-in options with the variant's added.
std::string variant_source(const std::vector<std::string>& roots, const KernelVariant& variant);
std::string variant_options(const std::string& options, const KernelVariant& variant);

// The renderer's root kernel files: the megakernel's, the wavefront's.
const std::vector<std::string>& renderer_kernel_files();
const std::vector<std::string>& wavefront_kernel_files();

}  // namespace clpath
