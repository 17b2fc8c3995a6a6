// clpath bench scaling: the triangle-count scaling benchmark (bench/scaling.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "bench/report_files.hpp"
#include "bench/scaling.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "shared_structs.h"
#include "util/error.hpp"

namespace clpath {
namespace {

struct ScalingCliOptions {
    double min = 100, max = 10'000'000;
    double time_cap = 60;
    std::string accel = "both", csv, md, device;
    int width = 480, height = 320, launches = 5;
    int path_width = 320, path_height = 240, path_spp = 4;
    bool quick = false, no_embree = false;
};

std::size_t whole_count(double v, const char* what) {
    if (!(v >= 100 && v <= 5e7) || v != std::floor(v))
        throw UsageError(std::string(what) + " " + plain_number(v) + ": expected a whole number of triangles from 100 to 50000000");
    return std::size_t(v);
}

int run_scaling_cli(const ScalingCliOptions& c) {
    ScalingOptions o;
    o.min = whole_count(c.min, "--min");
    o.max = whole_count(c.max, "--max");
    if (o.min > o.max) throw UsageError("--min " + std::to_string(o.min) + " is larger than --max " + std::to_string(o.max));
    o.time_cap_s = c.time_cap;
    o.bvh = c.accel != "flat";
    o.flat = c.accel != "bvh";
    o.ray_width = c.width;
    o.ray_height = c.height;
    o.launches = c.launches;
    o.path_width = c.path_width;
    o.path_height = c.path_height;
    o.path_spp = std::uint32_t(c.path_spp);
    o.embree = !c.no_embree;
    if (c.quick) {
        o.min = 100;
        o.max = std::min<std::size_t>(o.max, 1000);
        o.ray_width = 16;
        o.ray_height = 12;
        o.launches = 1;
        o.check = 0;
        o.path_width = 16;
        o.path_height = 12;
        o.path_spp = 1;
        // Every row is measured: the sizes are tiny, and a cap predicted from
        // one row's time would skip rows on a loaded machine and not on an idle one.
        o.time_cap_s = std::numeric_limits<double>::infinity();
    }
    if (o.ray_width % int(CLP_BATCH_TILE) || o.ray_height % int(CLP_BATCH_TILE))
        throw UsageError("--width and --height must be multiples of " + std::to_string(CLP_BATCH_TILE));
    if (!c.csv.empty()) check_report_path(c.csv, "--csv");
    if (!c.md.empty()) check_report_path(c.md, "--md");
    const DeviceInfo device = select_device(c.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: bench scaling %zu..%zu triangles (%s) on %s\n", o.min, o.max, c.accel.c_str(),
                 device.describe().c_str());
    const auto rows = run_scaling(ctx, o, [](const std::string& s) { std::printf("%s\n", s.c_str()); std::fflush(stdout); });
    const std::string md = scaling_markdown(rows, device.name);
    std::printf("\n%s", md.c_str());
    if (!c.csv.empty()) write_report_file(c.csv, scaling_csv(rows, device.name));
    if (!c.md.empty()) write_report_file(c.md, md);
    std::size_t mismatched = 0;
    for (const auto& r : rows) mismatched += r.mismatched;
    if (mismatched) {
        std::fprintf(stderr, "clpath: error: %zu rays disagree with the CPU reference\n", mismatched);
        return 3;
    }
    return 0;
}

}  // namespace

Command add_bench_scaling_command(CLI::App& bench) {
    auto o = std::make_shared<ScalingCliOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "scaling", "Triangle-count scaling: build time, SAH, memory, ray batches and path samples/s, BVH and flat");
    cmd->add_option("--min", o->min, "Fewest triangles (>= 100)")->capture_default_str();
    cmd->add_option("--max", o->max, "Most triangles (<= 50000000; sizes go in 1-3-10 steps)")->capture_default_str();
    cmd->add_option("--time-cap", o->time_cap, "Flat structure: stop before a size predicted to take longer (seconds)")
        ->check(real_number(0, 1e9, true))
        ->capture_default_str();
    cmd->add_option("--accel", o->accel, "Structures to measure: both, bvh, flat")
        ->check(CLI::IsMember({"both", "bvh", "flat"}))
        ->capture_default_str();
    cmd->add_option("--width", o->width,
                    "Ray batches: pixels across (multiple of " + std::to_string(CLP_BATCH_TILE) + "; x " +
                        std::to_string(CLP_BATCH_SAMPLES) + " samples)")
        ->check(whole_number(CLP_BATCH_TILE, 4096))
        ->capture_default_str();
    cmd->add_option("--height", o->height, "Ray batches: pixels down (multiple of " + std::to_string(CLP_BATCH_TILE) + ")")
        ->check(whole_number(CLP_BATCH_TILE, 4096))
        ->capture_default_str();
    cmd->add_option("--launches", o->launches, "Timed launches per batch")->check(whole_number(1, 100))->capture_default_str();
    cmd->add_option("--path-width", o->path_width, "Path column: the render's pixels across")
        ->check(whole_number(1, 4096))
        ->capture_default_str();
    cmd->add_option("--path-height", o->path_height, "Path column: the render's pixels down")
        ->check(whole_number(1, 4096))
        ->capture_default_str();
    cmd->add_option("--path-spp", o->path_spp, "Path column: samples per pixel")
        ->check(whole_number(1, 4096))
        ->capture_default_str();
    cmd->add_option("--csv", o->csv, "Write the table as CSV to this file");
    cmd->add_option("--md", o->md, "Write the table as Markdown to this file");
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_flag("--quick", o->quick, "100 and 1000 triangles at a tiny resolution (for CI)");
    cmd->add_flag("--no-embree", o->no_embree,
                  "Skip the Embree columns (by default Embree traces the BVH rows' batches too, in its default mode)");
    return [o] { return run_scaling_cli(*o); };
}

}  // namespace clpath
