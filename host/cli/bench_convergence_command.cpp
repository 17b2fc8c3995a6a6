// clpath bench convergence: not built yet (issue 6).
#include "cli/commands.hpp"
#include "util/error.hpp"

namespace clpath {

Command add_bench_convergence_command(CLI::App& bench) {
    bench.add_subcommand("convergence", "(not built yet)");
    return []() -> int { throw Error("clpath bench convergence is not built yet"); };
}

}  // namespace clpath
