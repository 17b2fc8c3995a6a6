// clpath bench scaling: not built yet (issue 6).
#include "cli/commands.hpp"
#include "util/error.hpp"

namespace clpath {

Command add_bench_scaling_command(CLI::App& bench) {
    bench.add_subcommand("scaling", "(not built yet)");
    return []() -> int { throw Error("clpath bench scaling is not built yet"); };
}

}  // namespace clpath
