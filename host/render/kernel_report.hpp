#pragma once
// The portability gate's work: clpath's programs (kernel_programs.hpp)
// written out as sources with their build options, and compiled for GPU
// targets offline (cl/offline_compile.hpp), with the resources of every
// kernel and the budgets the GPU code is held to.
#include <functional>
#include <string>
#include <vector>

#include "cl/embedded_sources.hpp"
#include "cl/offline_compile.hpp"
#include "render/kernel_programs.hpp"

namespace clpath {

// Writes DIR/<name>.cl (the program's full source, includes in place, as
// clpath hands it to clBuildProgram), DIR/<name>.options (its build options,
// one line) and DIR/programs.tsv (name, kernels, options, what selects it).
// Creates DIR; throws clpath::Error when it cannot.
// A variant (kernel files replacing embedded ones, options added) is written
// and compiled in place of the built-in kernels.
void write_program_dump(const std::vector<ProgramSpec>& programs, const std::string& dir,
                        const KernelVariant& variant = {});

struct ProgramCompile {
    const ProgramSpec* program = nullptr;
    OfflineResult result;
};

struct CompileRun {
    int jobs = 1;           // compiles at once
    std::string work_dir;   // each compile's files go to work_dir/<program>-<target>
    std::string cache_dir;  // results reused from here ("" for none)
    KernelVariant variant;  // compiled instead of the built-in kernels when not empty
    std::function<void(const ProgramCompile&)> on_done;  // as each finishes (any thread, serialised)
};

// Every program for every target whose tools are all there (missing_tools()),
// in program order, then target order.
std::vector<ProgramCompile> compile_programs(const std::vector<ProgramSpec>& programs,
                                             const std::vector<std::string>& targets,
                                             const OfflineToolchain& tools, const CompileRun& run);

// The most a kernel may use on a target: the traversal kernels are held to
// what GPU traversal kernels of their kind use (tinybvh 1.6.7's 4-wide and
// CWBVH kernels: 54-56 registers, 128-256 B stack at sm_90), so that an SM
// keeps 32 warps resident.
struct KernelBudget {
    const char* kernel;
    const char* target;
    int max_registers;
    int max_stack_bytes;
    const char* with_option;     // applies only to programs built with these options (space-separated; nullptr: any),
                                 // and then in place of the entries for any program
    const char* without_option;  // applies only to programs built without it (nullptr: any)
    // A kernel not yet within its budget is held at the figures it has today:
    // between the budget and these it is reported as an open shortfall (every
    // run lists it), over these it fails like any kernel over budget. Zero:
    // the budget itself is the limit.
    int held_registers = 0;
    int held_stack_bytes = 0;
};
const std::vector<KernelBudget>& kernel_budgets();

// "program kernel target: 95 registers > 64" lines for every kernel over its
// budget (programs compiled as GPU code only).
std::vector<std::string> budget_violations(const std::vector<ProgramCompile>& compiles);
// The same lines for kernels over their budget but within the figures they are held at.
std::vector<std::string> budget_shortfalls(const std::vector<ProgramCompile>& compiles);

// The rows as CSV (program,kernel,target,registers,sgprs,stack_bytes,spills,options,selected_by;
// a failed compile has kernel FAILED)
// and as a Markdown table.
std::string resources_csv(const std::vector<ProgramCompile>& compiles);
std::string resources_markdown(const std::vector<ProgramCompile>& compiles);

}  // namespace clpath
