// clpath bench {scaling, rays, instances, convergence, build, path, render-ab}: the benchmarks. Each subcommand
// lives in its own file; this one only groups them under `bench`.
#include <map>

#include "cli/commands.hpp"

namespace clpath {

Command add_bench_command(CLI::App& app) {
    CLI::App* bench = app.add_subcommand("bench", "Benchmarks: triangle-count scaling, ray batches, instancing, convergence, BVH build, path tracing against Embree, kernel variants");
    bench->require_subcommand(1);
    auto commands = std::make_shared<std::map<CLI::App*, Command>>();
    for (auto adder : {add_bench_scaling_command, add_bench_rays_command, add_bench_instances_command, add_bench_convergence_command,
                       add_bench_build_command, add_bench_path_command, add_bench_render_ab_command}) {
        const std::size_t before = bench->get_subcommands({}).size();
        Command run = adder(*bench);
        (*commands)[bench->get_subcommands({})[before]] = std::move(run);
    }
    return [bench, commands] {
        for (auto* sub : bench->get_subcommands())
            if (auto it = commands->find(sub); it != commands->end()) return it->second();
        return 2;
    };
}

}  // namespace clpath
