// clpath bench path: clpath's path tracer against an Embree one on the same
// scene (bench/path_bench.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/path_bench.hpp"
#include "bench/report_files.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"
#include "util/median.hpp"

namespace clpath {
namespace {

struct PathOptions {
    std::string scene;
    std::uint32_t spp = 16, max_depth = 4, seed = 0;
    int width = 0, height = 0, rounds = 3, threads = 0;
    std::string csv, device;
    bool quick = false;
};

int run_path(const PathOptions& o) {
    if (!o.csv.empty()) check_report_path(o.csv, "--csv");
    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    PathBenchOptions bo;
    bo.spp = o.spp;
    bo.max_depth = o.max_depth;
    bo.rounds = o.rounds;
    bo.seed = o.seed;
    bo.threads = o.threads;
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    if (o.quick) {
        scene.camera.width = 32;
        scene.camera.height = 32;
        bo.spp = 64;
        bo.rounds = 1;
    }
    // Refused before any device is opened: the scene alone decides.
    try {
        check_path_bench_scene(scene);
    } catch (const UsageError& e) {
        throw UsageError(o.scene + ": " + e.what());
    }
    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: bench path '%s' (%zu triangles) at %dx%d, %u spp, depth %u, %d round%s\n",
                 scene.name.c_str(), scene.triangle_count(), scene.camera.width, scene.camera.height, bo.spp,
                 bo.max_depth, bo.rounds, bo.rounds == 1 ? "" : "s");
    PathBenchResult r;
    try {
        r = run_path_bench(ctx, scene, bo, [](const std::string& s) { std::fprintf(stderr, "clpath: %s\n", s.c_str()); });
    } catch (const UsageError&) {
        throw;
    } catch (const Error& e) {
        throw Error(o.scene + ": " + e.what());
    }
    std::vector<double> cs, cr;
    std::vector<double> es[2], er[2], rs[2], rr[2];  // by EmbreeMode
    std::uint64_t crays = 0, erays[2] = {0, 0};
    for (const auto& p : r.rounds) {
        cs.push_back(p.clpath.msamples_per_s);
        cr.push_back(p.clpath.mrays_per_s);
        crays = p.clpath.rays;
        for (EmbreeMode m : kEmbreeModes) {
            const int i = int(m);
            es[i].push_back(p.embree[i].msamples_per_s);
            er[i].push_back(p.embree[i].mrays_per_s);
            rs[i].push_back(p.samples_ratio(m));
            rr[i].push_back(p.rays_ratio(m));
            erays[i] = p.embree[i].rays;
        }
    }
    const double samples = double(r.spp) * r.width * r.height;
    std::printf("scene: %s, %zu triangles, %dx%d, %u spp, max depth %u, path integrator (NEE + MIS), no Russian roulette, "
                "%zu rounds\n",
                r.scene.c_str(), r.triangles, r.width, r.height, r.spp, r.max_depth, r.rounds.size());
    std::printf("clpath: %s: median %.3f Msamples/s, %.3f Mrays/s (%.3f rays per sample)\n", r.clpath_device.c_str(),
                median_of(cs), median_of(cr), double(crays) / samples);
    // The default mode first: it is how Embree's users run it; robust is the like-for-like (watertight) guarantee.
    for (EmbreeMode m : kEmbreeModes) {
        const int i = int(m);
        std::printf("Embree %s mode: %s: median %.3f Msamples/s, %.3f Mrays/s (%.3f rays per sample)\n",
                    embree_mode_name(m), r.embree[i].c_str(), median_of(es[i]), median_of(er[i]),
                    double(erays[i]) / samples);
    }
    for (EmbreeMode m : kEmbreeModes) {
        const int i = int(m);
        std::printf("clpath/Embree %s mode: %.3f (Msamples/s), %.3f (Mrays/s), medians of the per-round ratios\n",
                    embree_mode_name(m), median_of(rs[i]), median_of(rr[i]));
    }
    for (EmbreeMode m : kEmbreeModes)
        std::printf("agreement with Embree %s mode (clpath / Embree image means): %s: %s\n", embree_mode_name(m),
                    r.agreement[int(m)].describe().c_str(), r.agreement[int(m)].agrees() ? "agree" : "DISAGREE");
    if (!o.csv.empty()) {
        std::ostringstream csv;
        csv << "round,scene,triangles,width,height,spp,max_depth,clpath_device,clpath_s,clpath_rays,"
               "clpath_msamples_per_s,clpath_mrays_per_s";
        for (EmbreeMode m : kEmbreeModes) {
            const std::string e = std::string("embree_") + embree_mode_name(m);
            csv << "," << e << "," << e << "_s," << e << "_rays," << e << "_msamples_per_s," << e << "_mrays_per_s,"
                << "samples_ratio_" << embree_mode_name(m) << ",rays_ratio_" << embree_mode_name(m) << ",max_abs_z_"
                << embree_mode_name(m) << ",z_bound_" << embree_mode_name(m);
        }
        csv << "\n";
        for (std::size_t i = 0; i < r.rounds.size(); ++i) {
            const auto& p = r.rounds[i];
            char a[200], b[200];
            std::snprintf(a, sizeof a, "%zu,%s,%zu,%d,%d,%u,%u,", i + 1, csv_field(r.scene).c_str(), r.triangles, r.width,
                          r.height, r.spp, r.max_depth);
            std::snprintf(b, sizeof b, ",%.4f,%llu,%.4f,%.4f", p.clpath.seconds, (unsigned long long)p.clpath.rays,
                          p.clpath.msamples_per_s, p.clpath.mrays_per_s);
            csv << a << csv_field(r.clpath_device) << b;
            for (EmbreeMode m : kEmbreeModes) {
                const PathAgreement& ag = r.agreement[int(m)];
                double max_z = ag.max_region_z;
                for (double z : ag.z) max_z = std::max(max_z, std::fabs(z));
                const PathTiming& e = p.embree[int(m)];
                char c[200];
                std::snprintf(c, sizeof c, ",%.4f,%llu,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f", e.seconds,
                              (unsigned long long)e.rays, e.msamples_per_s, e.mrays_per_s, p.samples_ratio(m),
                              p.rays_ratio(m), max_z, ag.bound);
                csv << "," << csv_field(r.embree[int(m)]) << c;
            }
            csv << "\n";
        }
        write_report_file(o.csv, csv.str());
        std::fprintf(stderr, "clpath: wrote %s\n", o.csv.c_str());
    }
    if (!r.agrees()) {
        std::fprintf(stderr, "clpath: error: the clpath and Embree images disagree beyond their noise (see the z-scores): "
                             "the two tracers do not compute the same estimator, so their speeds are not comparable\n");
        return 3;
    }
    return 0;
}

}  // namespace

Command add_bench_path_command(CLI::App& bench) {
    auto o = std::make_shared<PathOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "path",
        "Path tracing against Embree: clpath's renderer (`render --max-depth D --rr none`) and an Embree path tracer "
        "with the same estimator, Embree in its default mode and robust, interleaved rounds, Msamples/s and Mrays/s, "
        "images checked to agree. Scenes of "
        "diffuse surfaces lit by emissive triangles and point, spot or directional lights only");
    cmd->add_option("scene", o->scene, scene_argument_help())->required();
    cmd->add_option("--spp", o->spp, "Samples per pixel per round")->check(whole_number(2, 1u << 20))->capture_default_str();
    cmd->add_option("--max-depth", o->max_depth, "Bounces, every path traced to it (no Russian roulette)")
        ->check(whole_number(0, 1024))
        ->capture_default_str();
    cmd->add_option("--width", o->width, "Image width (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Image height (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--rounds", o->rounds, "Rounds, each rendering with clpath then Embree; medians are reported")
        ->check(whole_number(1, 1000))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "clpath's seed (Embree's is seed + 1, so the two images are independent)")
        ->check(whole_number(0, 4294967294u))
        ->capture_default_str();
    cmd->add_option("--threads", o->threads, "Embree's threads (0: every hardware thread)")
        ->check(whole_number(0, 1024))
        ->capture_default_str();
    cmd->add_option("--csv", o->csv, "Write the rounds as CSV to this file");
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_flag("--quick", o->quick, "32x32 pixels, 64 spp, one round (for CI)");
    return [o] { return run_path(*o); };
}

}  // namespace clpath
