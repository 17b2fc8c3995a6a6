// clpath bench rays: the ray-batch traversal benchmark (bench/ray_batches.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/embree_baseline.hpp"
#include "bench/ray_batches.hpp"
#include "bench/ray_files.hpp"
#include "bench/report_files.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/kernel_variant_option.hpp"
#include "cli/option_checks.hpp"
#include "scene/load/scene_loader.hpp"
#include "shared_structs.h"
#include "util/error.hpp"

namespace clpath {
namespace {

struct RaysOptions {
    std::string scene;
    int width = 480, height = 320;
    std::string camera, light, csv, device, accel = "bvh", save_rays, ab_kernels, ab_options;
    int launches = 5;
    std::size_t workgroup = 64, check = std::size_t(1) << 18;
    std::uint32_t seed = 0;
    bool quick = false;
    bool no_embree = false;
};

// "1,2.5,-3" -> {1, 2.5, -3}; what names the option in messages.
std::vector<float> parse_numbers(const std::string& text, const std::string& what) {
    std::vector<float> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        const float x = std::strtof(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(x))
            throw Error(what + " '" + text + "': '" + item + "' is not a finite number");
        v.push_back(x);
    }
    return v;
}

int run_rays(const RaysOptions& o) {
    RayBenchOptions bo;
    bo.width = o.quick ? 32 : o.width;
    bo.height = o.quick ? 24 : o.height;
    bo.launches = o.quick ? 1 : o.launches;
    bo.workgroup = o.workgroup;
    bo.accel = parse_accel(o.accel);
    bo.check = o.quick ? 0 : o.check;
    bo.seed = o.seed;
    bo.embree = !o.no_embree;
    if (!o.light.empty()) {
        const auto l = parse_numbers(o.light, "--light");
        if (l.size() != 3) throw Error("--light '" + o.light + "': expected x,y,z");
        bo.light = glm::vec3(l[0], l[1], l[2]);
    }
    if (!o.csv.empty()) check_report_path(o.csv, "--csv");
    if (!o.save_rays.empty()) check_ray_folder(o.save_rays, "--save-rays");
    bo.ab = read_kernel_variant(o.ab_kernels, o.ab_options);

    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    if (!o.camera.empty()) {
        const auto c = parse_numbers(o.camera, "--camera");
        if (c.size() != 6 && c.size() != 7)
            throw Error("--camera '" + o.camera + "': expected eye_x,eye_y,eye_z,target_x,target_y,target_z[,vfov_degrees]");
        scene.camera.eye = {c[0], c[1], c[2]};
        scene.camera.target = {c[3], c[4], c[5]};
        scene.camera.up = {0, 1, 0};
        if (c.size() == 7) scene.camera.vfov_degrees = c[6];
    }
    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: bench rays '%s' (%zu triangles, %s) at %dx%d x %u samples on %s\n", scene.name.c_str(),
                 scene.triangle_count(), accel_name(bo.accel), bo.width, bo.height, CLP_BATCH_SAMPLES,
                 device.describe().c_str());
    // Each batch's file is written whole (through a rename) once traced; a
    // run that fails later removes the ones it wrote, so a folder never holds
    // part of a run.
    std::vector<std::string> saved;
    auto save = [&](const std::string& name, const std::string& bytes) {
        const std::string path = (std::filesystem::path(o.save_rays) / name).string();
        write_report_file(path, bytes);
        saved.push_back(path);
    };
    if (!o.save_rays.empty()) {
        bo.on_traced = [&](RayBatchKind kind, const std::vector<BatchRay>& rays, const std::vector<float>& result) {
            save(ray_file_name(kind), encode_ray_file(kind, rays, result));
        };
        bo.on_structure = [&](const std::string& source, const std::string& options,
                              const std::vector<unsigned char>& nodes, const BvhTriangles& triangles) {
            save(kBatchKernelsFile, source);
            save(kBatchOptionsFile, options + "\n");
            save(kNodesFile, std::string(nodes.begin(), nodes.end()));
            save(kTrianglesFile, std::string(reinterpret_cast<const char*>(triangles.data()),
                                             triangles.size() * sizeof(TriVerts)));
        };
    }
    RayBenchResult r;
    try {
        r = run_ray_bench(ctx, scene, bo, [](const std::string& s) { std::fprintf(stderr, "clpath: %s\n", s.c_str()); });
    } catch (const Error& e) {
        std::error_code ec;
        for (const auto& p : saved) std::filesystem::remove(p, ec);
        throw Error(o.scene + ": " + e.what());
    }
    for (const auto& p : saved) std::fprintf(stderr, "clpath: wrote %s\n", p.c_str());
    std::printf("scene: %s, %zu triangles, %s (%zu nodes, SAH %.2f, %.1f bytes per triangle), light %g,%g,%g, "
                "work-group %zu, device \"%s\"\n",
                r.scene.c_str(), r.triangles, accel_name(r.accel), r.structure.node_count, r.structure.sah_cost,
                double(r.structure_bytes) / double(r.triangles), r.light.x, r.light.y, r.light.z, bo.workgroup,
                r.device.c_str());
    for (const auto& k : r.kernels) std::printf("kernel %s\n", describe(k).c_str());
    for (EmbreeMode m : kEmbreeModes)
        if (!r.embree[int(m)].empty()) std::printf("CPU baseline: %s\n", r.embree[int(m)].c_str());
    bool agree = true;
    for (const auto& b : r.batches) {
        std::printf("%s\n", describe(b).c_str());
        for (EmbreeMode m : kEmbreeModes)
            if (b.embree_in(m).ran) std::printf("%s\n", describe_embree(b, m).c_str());
        if (b.ab.ran) std::printf("%s\n", describe_ab(b).c_str());
        agree = agree && b.agreement.agrees();
    }
    if (!o.csv.empty()) {
        std::ostringstream csv;
        csv << "device,scene,triangles,accel,batch,width,height,workgroup,rays,hits,launches,mean_ms,best_ms,"
               "mrays_per_s,checked,identical_percent,ties,near_origin,mismatched,max_dt,embree_default_mean_ms,"
               "embree_default_mrays_per_s,clpath_over_embree_default,embree_default_mismatched,embree_robust_mean_ms,"
               "embree_robust_mrays_per_s,clpath_over_embree_robust,embree_robust_mismatched\n";
        for (const auto& b : r.batches) {
            char line[512];
            std::snprintf(line, sizeof line, ",%zu,%s,%s,%d,%d,%zu,%zu,%zu,%zu,%.4f,%.4f,%.3f,%zu,%.4f,%zu,%zu,%zu,%.3g\n",
                          r.triangles, accel_name(r.accel), b.name.c_str(), bo.width, bo.height, bo.workgroup, b.rays,
                          b.hits, b.launch_ms.size(), b.mean_ms, b.best_ms, b.mrays_per_s, b.agreement.checked,
                          b.agreement.identical_percent(), b.agreement.ties, b.agreement.near_origin, b.agreement.mismatched,
                          b.agreement.max_dt);
            // Embree's columns, default mode first, stay empty when it did not
            // run (built without it, or --no-embree).
            std::string embree;
            for (EmbreeMode m : kEmbreeModes) {
                const EmbreeBatch& e = b.embree_in(m);
                char cols[160] = ",,,,";
                if (e.ran)
                    std::snprintf(cols, sizeof cols, ",%.4f,%.3f,%.4f,%zu", e.mean_ms, e.mrays_per_s, b.over_embree(m),
                                  e.agreement.mismatched);
                embree += cols;
            }
            std::string row = line;
            row.insert(row.size() - 1, embree);  // before the newline
            csv << csv_field(r.device) << "," << csv_field(r.scene) << row;
        }
        write_report_file(o.csv, csv.str());
        std::fprintf(stderr, "clpath: wrote %s\n", o.csv.c_str());
    }
    if (!agree) {
        std::fprintf(stderr, "clpath: error: the device's hits disagree with the CPU reference (see 'mismatched')\n");
        return 3;
    }
    return 0;
}

}  // namespace

Command add_bench_rays_command(CLI::App& bench) {
    auto o = std::make_shared<RaysOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "rays", "Ray-batch traversal benchmark: primary, shadow and diffuse batches, Mrays/s, checked on the CPU");
    cmd->add_option("scene", o->scene, scene_argument_help())
        ->required();
    const std::string tile = std::to_string(CLP_BATCH_TILE);
    cmd->add_option("--width", o->width, "Pixels across (a multiple of " + tile + ")")
        ->check(whole_number(CLP_BATCH_TILE, 16384))
        ->capture_default_str();
    cmd->add_option("--height", o->height, "Pixels down (a multiple of " + tile + ")")
        ->check(whole_number(CLP_BATCH_TILE, 16384))
        ->capture_default_str();
    cmd->add_option("--camera", o->camera, "eye_x,eye_y,eye_z,target_x,target_y,target_z[,vfov] (default: the scene's)");
    cmd->add_option("--light", o->light,
                    "Point light x,y,z for the shadow rays (default: the scene's point light, else just below its "
                    "emitters, else above its bounding box)");
    cmd->add_option("--launches", o->launches, "Timed launches per batch, after one warm-up")
        ->check(whole_number(1, 1000))
        ->capture_default_str();
    cmd->add_option("--workgroup", o->workgroup, "Work-items per work-group (0: the driver chooses)")
        ->check(whole_number(0, std::uint64_t(1) << 20))
        ->capture_default_str();
    cmd->add_option("--accel", o->accel, "Acceleration structure: bvh, or flat (one box per object)")
        ->check(CLI::IsMember(accel_names()))
        ->capture_default_str();
    cmd->add_option("--check", o->check, "Rays per batch checked against the CPU reference, evenly spaced (0: all)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the diffuse directions")->check(whole_number(0, 4294967295u))->capture_default_str();
    cmd->add_option("--csv", o->csv, "Write the results as CSV to this file");
    cmd->add_option("--save-rays", o->save_rays,
                    "Write each batch's rays and clpath's hits to primary.rays, shadow.rays and diffuse.rays in this "
                    "existing folder, with the batch kernels' program, nodes and triangles (format: "
                    "host/bench/ray_files.hpp), for tracing them with another tracer");
    add_kernel_variant_options(cmd, &o->ab_kernels, &o->ab_options, "the batch kernels",
                               "each batch prints the variant's speed over the built-in kernels' (median of the "
                               "launch pairs, quartiles) and how many answers differ");
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_flag("--quick", o->quick, "32x24 pixels, one timed launch, every ray checked (for CI)");
    cmd->add_flag("--no-embree", o->no_embree,
                  embree_built_in() ? "Skip the Embree CPU baselines (by default Embree traces every batch too, in its default "
                                      "mode and robust)"
                                    : "Skip the Embree CPU baseline (this build has none)");
    return [o] { return run_rays(*o); };
}

}  // namespace clpath
