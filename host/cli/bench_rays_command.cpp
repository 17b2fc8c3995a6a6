// clpath bench rays: not built yet (issue 6).
#include "cli/commands.hpp"
#include "util/error.hpp"

namespace clpath {

Command add_bench_rays_command(CLI::App& bench) {
    bench.add_subcommand("rays", "(not built yet)");
    return []() -> int { throw Error("clpath bench rays is not built yet"); };
}

}  // namespace clpath
