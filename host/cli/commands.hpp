#pragma once
// The subcommands of the clpath program. Each registers its options on the
// CLI11 app and returns the function that runs it.
#include <functional>

#include <CLI/CLI.hpp>

namespace clpath {

using Command = std::function<int()>;

Command add_render_command(CLI::App& app);
Command add_devices_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_view_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_export_command(CLI::App& app);
Command add_kernels_command(CLI::App& app);

// The subcommands of `clpath bench`.
Command add_bench_scaling_command(CLI::App& bench);
Command add_bench_rays_command(CLI::App& bench);
Command add_bench_instances_command(CLI::App& bench);
Command add_bench_convergence_command(CLI::App& bench);
Command add_bench_build_command(CLI::App& bench);
Command add_bench_path_command(CLI::App& bench);
Command add_bench_render_ab_command(CLI::App& bench);

}  // namespace clpath
