// clpath bench build: BVH build time alone (no device needed), repeated, with
// the median, build Mtris/s and the tree's SAH cost.
#include <algorithm>
#include <ctime>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/report_files.hpp"
#include "bvh/bvh.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

struct BuildBenchOptions {
    std::string scene, csv;
    int threads = 0, repeat = 3;
    BvhBuildOptions bvh;
};

int run_build(const BuildBenchOptions& o) {
    if (!o.csv.empty()) check_report_path(o.csv, "--csv");
    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    BvhBuildOptions opt = o.bvh;
    opt.threads = o.threads;
    const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::fprintf(stderr, "clpath: bench build '%s' (%zu triangles), %d thread%s, %d runs\n", scene.name.c_str(),
                 scene.triangle_count(), threads, threads == 1 ? "" : "s", o.repeat);
    // CPU time beside wall time: on a shared machine the wall time includes
    // waiting for a core, the CPU time (all threads) does not.
    auto cpu_ms = [] {
        timespec ts{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
        return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
    };
    std::vector<double> ms;
    BvhStats stats;
    for (int r = 0; r < o.repeat; ++r) {
        const double c0 = cpu_ms();
        const Bvh bvh = build_bvh(scene.vertices, opt);
        const double cpu = cpu_ms() - c0;
        stats = bvh.stats;
        ms.push_back(stats.build_ms);
        std::printf("run %d: %.2f ms, CPU time %.2f ms\n", r + 1, stats.build_ms, cpu);
    }
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double mtris = double(scene.triangle_count()) / (median * 1e-3) * 1e-6;
    std::printf("scene: %s, %zu triangles, %d threads, median %.2f ms of %d, %.2f Mtris/s, SAH %.2f, %zu nodes, "
                "%zu leaves, depth %d\n",
                scene.name.c_str(), scene.triangle_count(), threads, median, o.repeat, mtris, stats.sah_cost,
                stats.node_count, stats.leaf_count, stats.max_depth);
    if (!o.csv.empty()) {
        std::ostringstream csv;
        csv << "scene,triangles,threads,runs,median_ms,min_ms,max_ms,mtris_per_s,sah_cost,nodes,leaves,depth\n";
        char line[256];
        std::snprintf(line, sizeof line, ",%zu,%d,%d,%.3f,%.3f,%.3f,%.3f,%.4f,%zu,%zu,%d\n", scene.triangle_count(),
                      threads, o.repeat, median, sorted.front(), sorted.back(), mtris, stats.sah_cost, stats.node_count,
                      stats.leaf_count, stats.max_depth);
        csv << csv_field(scene.name) << line;
        write_report_file(o.csv, csv.str());
        std::fprintf(stderr, "clpath: wrote %s\n", o.csv.c_str());
    }
    return 0;
}

}  // namespace

Command add_bench_build_command(CLI::App& bench) {
    auto o = std::make_shared<BuildBenchOptions>();
    CLI::App* cmd = bench.add_subcommand("build", "BVH build time: median of repeated builds, Mtris/s, SAH cost");
    cmd->add_option("scene", o->scene, scene_argument_help())
        ->required();
    cmd->add_option("--threads", o->threads, "Build threads (0: all hardware threads)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    cmd->add_option("--repeat", o->repeat, "Builds to time; the median is reported")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--bins", o->bvh.bins, "SAH bins per axis")->check(CLI::Range(2, 256))->capture_default_str();
    cmd->add_option("--leaf", o->bvh.max_leaf_size, "Triangles per leaf at most")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    cmd->add_option("--csv", o->csv, "Write the result as CSV to this file");
    return [o] { return run_build(*o); };
}

}  // namespace clpath
