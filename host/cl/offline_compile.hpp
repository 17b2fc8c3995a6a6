#pragma once
// Compiling an OpenCL program for GPU targets without a GPU or its driver,
// with the open toolchains a driver is built from: clang's OpenCL front end,
// libclc's built-ins linked in as bitcode, LLVM's optimiser and back end, and
// for NVIDIA the vendor's own assembler (ptxas from the CUDA toolkit), which
// allocates registers as the driver would. For every kernel it reports the
// registers, the stack (NVIDIA) or private segment (AMD) and the spills.
//
//   NVIDIA sm_90:      clang-14 -target nvptx64-nvidia-nvcl, llvm-link-14 with libclc's
//                      nvptx64--nvidiacl.bc, opt-14 -O3, llc-14 (PTX 7.5), ptxas -arch=sm_90 -v
//   AMD gfx90a:        clang-14 -target amdgcn-amd-amdhsa, libclc's amdgcn--amdhsa.bc,
//                      opt-14 -O3, llc-14; the kernel descriptors' metadata
//   AMD gfx1100:       the same with clang-15, opt-15, llc-15 (LLVM 14 has no gfx11) and
//                      libclc 14's bitcode (Debian's libclc-15 replaces libclc-14)
//
// A symbol left undefined after linking the built-ins (a function the
// front end emitted no body for, as for a plain C99 `inline`) is an error
// on every target, as a driver's link would make it.
#include <cstdint>
#include <string>
#include <vector>

namespace clpath {

// "sm_90", "gfx90a", "gfx1100".
const std::vector<std::string>& gpu_target_names();
bool is_nvidia_target(const std::string& target);

// Where the tools are; found on PATH (and ptxas in /usr/local/cuda/bin), or
// named by CLPATH_PTXAS and CLPATH_LIBCLC_DIR.
struct OfflineToolchain {
    std::string clang14, link14, opt14, llc14, nm14;
    std::string clang15, link15, opt15, llc15, nm15;
    std::string ptxas;
    std::string libclc_dir;  // holds nvptx64--nvidiacl.bc and amdgcn--amdhsa.bc
};
OfflineToolchain find_offline_toolchain();
// What a target needs that is not there ("" when nothing is missing).
std::string missing_tools(const OfflineToolchain& tools, const std::string& target);
// The tools' versions, one line each, for reports.
std::string toolchain_versions(const OfflineToolchain& tools);

struct KernelResources {
    std::string kernel;
    int registers = 0;    // NVIDIA: registers per thread; AMD: VGPRs per lane
    int sgprs = 0;        // AMD scalar registers (0 for NVIDIA)
    int stack_bytes = 0;  // NVIDIA: cumulative stack frame; AMD: private segment per lane
    int spill_bytes = 0;  // NVIDIA: spill stores + loads (bytes); AMD: VGPRs + SGPRs spilled (count)
};

struct OfflineResult {
    std::string target;
    bool ok = false;
    std::string log;                      // what failed, with the tool's message
    std::vector<KernelResources> kernels;  // per kernel, in the tool's order
    bool from_cache = false;
    double seconds = 0;  // wall time of the compile (0 from the cache)
};

// Compiles source (includes already in place, program_source) with options
// (as clBuildProgram would get them) for target, in work_dir (created; files
// left there). With a cache_dir, a result for the same source, options,
// target and tool versions is read from it instead (and stored there).
OfflineResult compile_offline(const OfflineToolchain& tools, const std::string& target, const std::string& source,
                              const std::string& options, const std::string& work_dir,
                              const std::string& cache_dir = "");

// The parsers, exposed for tests: ptxas -v's report and the AMDGPU
// assembly's kernel metadata (.amdgpu_metadata, one entry per kernel).
std::vector<KernelResources> parse_ptxas_report(const std::string& text);
std::vector<KernelResources> parse_amdgpu_metadata(const std::string& assembly);
// Undefined symbols in llvm-nm --undefined-only output, LLVM intrinsics left out.
std::vector<std::string> parse_undefined_symbols(const std::string& nm_output);

}  // namespace clpath
