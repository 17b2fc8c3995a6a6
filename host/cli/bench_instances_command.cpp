// clpath bench instances: the ray batches on an instanced scene, traced by
// the two-level walk, flattened, and by Embree both ways (bench/instance_batches.hpp).
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include "bench/embree_baseline.hpp"
#include "bench/instance_batches.hpp"
#include "bench/report_files.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "scene/load/scene_loader.hpp"
#include "shared_structs.h"
#include "util/error.hpp"

namespace clpath {
namespace {

struct InstancesOptions {
    std::string scene, csv, device;
    int width = 480, height = 320, launches = 5;
    std::size_t workgroup = 64, flatten_limit = 50'000'000;
    std::uint32_t seed = 0;
    bool quick = false, no_embree = false;
};

int run_instances(const InstancesOptions& o) {
    InstanceBenchOptions bo;
    bo.width = o.quick ? 32 : o.width;
    bo.height = o.quick ? 24 : o.height;
    bo.launches = o.quick ? 1 : o.launches;
    bo.workgroup = o.workgroup;
    bo.seed = o.seed;
    bo.embree = !o.no_embree;
    bo.flatten_limit = o.flatten_limit;
    if (!o.csv.empty()) check_report_path(o.csv, "--csv");
    const Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: bench instances '%s' (%zu instances, %zu triangles placed) at %dx%d x %u samples on %s\n",
                 scene.name.c_str(), scene.instances.size(), scene.placed_triangle_count(), bo.width, bo.height,
                 CLP_BATCH_SAMPLES, device.describe().c_str());
    InstanceBenchResult r;
    try {
        r = run_instance_bench(ctx, scene, bo, [](const std::string& s) { std::fprintf(stderr, "clpath: %s\n", s.c_str()); });
    } catch (const Error& e) {
        throw Error(o.scene + ": " + e.what());
    }
    const TwoLevelStats& t = r.two_level;
    std::printf("scene: %s, %zu instances of %zu stored triangles, %zu placed, light %g,%g,%g, work-group %zu, device "
                "\"%s\"\n",
                r.scene.c_str(), r.instances, r.stored_triangles, r.placed_triangles, r.light.x, r.light.y, r.light.z,
                bo.workgroup, r.device.c_str());
    std::printf("two-level: %zu bytes (top level %zu, depth %d, built in %.2f ms; bottom levels built in %.2f ms)\n",
                r.instanced_bytes, t.top_bytes, t.top_depth, t.top_build_ms, t.bottom_build_ms);
    if (r.flattened)
        std::printf("flattened: %zu bytes (%.1fx the two-level), built in %.2f ms\n", r.flattened_bytes,
                    double(r.flattened_bytes) / double(r.instanced_bytes), r.flattened_build_ms);
    else
        std::printf("flattened: not traced (%s)\n", r.not_flattened.c_str());
    for (std::size_t i = 0; i < kInstanceTracers; ++i)
        if (!r.baselines[i].empty())
            std::printf("CPU baseline (%s): %s\n", instance_tracer_name(InstanceTracer(i)), r.baselines[i].c_str());
    for (const auto& b : r.batches) std::printf("%s\n", describe(b).c_str());
    if (!o.csv.empty()) {
        std::ostringstream csv;
        csv << "device,scene,instances,placed_triangles,batch,width,height,rays,tracer,hits,launches,mean_ms,best_ms,"
               "mrays_per_s,clpath_instanced_over_this,differing,near_origin\n";
        for (const auto& b : r.batches)
            for (std::size_t i = 0; i < kInstanceTracers; ++i) {
                const TracerPass& p = b.by[i];
                if (!p.ran) continue;
                char line[400];
                std::snprintf(line, sizeof line, ",%zu,%zu,%s,%d,%d,%zu,%s,%zu,%d,%.4f,%.4f,%.3f,%.4f,%zu,%zu\n",
                              r.instances, r.placed_triangles, b.name.c_str(), bo.width, bo.height, b.rays,
                              instance_tracer_name(InstanceTracer(i)), p.hits, bo.launches, p.mean_ms, p.best_ms,
                              p.mrays_per_s, i == 0 ? 1.0 : b.ratio(InstanceTracer(i)), p.differing, p.near_origin);
                csv << csv_field(r.device) << "," << csv_field(r.scene) << line;
            }
        write_report_file(o.csv, csv.str());
        std::fprintf(stderr, "clpath: wrote %s\n", o.csv.c_str());
    }
    return 0;
}

}  // namespace

Command add_bench_instances_command(CLI::App& bench) {
    auto o = std::make_shared<InstancesOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "instances",
        "Instancing benchmark: the ray batches of 'bench rays' on an instanced scene (bunnies:N, or a scene file "
        "with instances), traced by the two-level walk, by the one-level BVH over the scene flattened, and by "
        "Embree over the instances and flattened; Mrays/s, ratios, rays whose answers differ");
    cmd->add_option("scene", o->scene, scene_argument_help())->required();
    const std::string tile = std::to_string(CLP_BATCH_TILE);
    cmd->add_option("--width", o->width, "Pixels across (a multiple of " + tile + ")")
        ->check(whole_number(CLP_BATCH_TILE, 16384))
        ->capture_default_str();
    cmd->add_option("--height", o->height, "Pixels down (a multiple of " + tile + ")")
        ->check(whole_number(CLP_BATCH_TILE, 16384))
        ->capture_default_str();
    cmd->add_option("--launches", o->launches, "Timed launches (Embree: passes) per batch, after one warm-up")
        ->check(whole_number(1, 1000))
        ->capture_default_str();
    cmd->add_option("--workgroup", o->workgroup, "Work-items per work-group (0: the driver chooses)")
        ->check(whole_number(0, std::uint64_t(1) << 20))
        ->capture_default_str();
    cmd->add_option("--flatten-limit", o->flatten_limit,
                    "Trace the flattened scene too while it places at most this many triangles")
        ->check(whole_number(0, std::uint64_t(1) << 31))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the diffuse directions")->check(whole_number(0, 4294967295u))->capture_default_str();
    cmd->add_option("--csv", o->csv, "Write the results as CSV to this file");
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_flag("--quick", o->quick, "32x24 pixels, one timed launch (for CI)");
    cmd->add_flag("--no-embree", o->no_embree,
                  embree_built_in() ? "Skip the Embree CPU baselines" : "Skip the Embree CPU baselines (this build has none)");
    return [o] { return run_instances(*o); };
}

}  // namespace clpath
