// clpath bench convergence SCENE --reference REF: how fast each estimator
// configuration's error against a reference falls, in samples and in seconds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench/convergence.hpp"
#include "bench/convergence_report.hpp"
#include "bench/estimator_configs.hpp"
#include "bench/series_exchange.hpp"
#include "cl/context.hpp"
#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "mpi/launch.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"
#include "util/text_file.hpp"

namespace clpath {
namespace {

struct ConvergenceArgs {
    std::string scene, reference, csv, md, device;
    std::vector<std::string> configs;
    std::uint64_t max_spp = 0;  // 0: 1024, or 16 with --quick
    double time_cap = 0;
    int width = 0, height = 0;
    CompareOptions compare;
    bool quick = false;
};

std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// The render size: as asked, else the reference's (in quick mode divided by
// the smallest integer that brings the width to at most 32 pixels and divides
// both sides, so that the reference can be reduced exactly).
void choose_size(const ConvergenceArgs& o, const Image& ref, int& width, int& height) {
    width = o.width;
    height = o.height;
    if (width && !height) height = std::max(1, int(std::lround(double(width) * ref.height / ref.width)));
    if (height && !width) width = std::max(1, int(std::lround(double(height) * ref.width / ref.height)));
    if (width) return;
    int k = 1;
    if (o.quick)
        for (int c = std::max(1, (ref.width + 31) / 32); c <= ref.width; ++c)
            if (ref.width % c == 0 && ref.height % c == 0) {
                k = c;
                break;
            }
    width = ref.width / k;
    height = ref.height / k;
}

int run_convergence(const ConvergenceArgs& o) {
    // Everything that can be checked is checked before any rendering.
    for (const auto& out : {o.csv, o.md})
        if (!out.empty()) check_text_output_path(out);
    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    const Image full_ref = read_image(o.reference);
    for (float v : full_ref.rgb)
        if (!std::isfinite(v)) throw Error(o.reference + ": the reference has NaN or infinite pixels");
    int width = 0, height = 0;
    choose_size(o, full_ref, width, height);
    const Image reference = reference_at(full_ref, width, height, o.reference);
    if (std::abs(double(scene.camera.width) / scene.camera.height - double(width) / height) > 1e-3)
        std::fprintf(stderr, "clpath: warning: %s is %dx%d, the scene's camera %dx%d: the aspect ratios differ\n",
                     o.reference.c_str(), full_ref.width, full_ref.height, scene.camera.width, scene.camera.height);
    scene.camera.width = width;
    scene.camera.height = height;

    ConvergenceLimits limits;
    limits.max_spp = o.max_spp ? o.max_spp : (o.quick ? 16 : 1024);
    limits.time_cap = o.time_cap;
    std::vector<EstimatorConfig> configs;
    for (const auto* list : {&estimator_configs(), &light_sampler_configs()})
        for (const auto& c : *list)
            if (o.configs.empty() ? list == &estimator_configs()
                                  : std::find(o.configs.begin(), o.configs.end(), c.name) != o.configs.end())
                configs.push_back(c);

    const DeviceInfo device = select_device(o.device);
    Context ctx(device);
    std::fprintf(stderr, "clpath: convergence of '%s' at %dx%d against %s%s, up to %llu spp, on %s\n",
                 scene.name.c_str(), width, height, o.reference.c_str(),
                 width == full_ref.width ? "" : " (reduced by block means)", (unsigned long long)limits.max_spp,
                 device.describe().c_str());

    // Over MPI ranks, configuration i is measured on rank i mod ranks, and
    // rank 0 gathers the series: a study ends in its time divided by the ranks.
    const int rank = mpi_rank(), ranks = mpi_size();
    std::vector<ConvergenceSeries> series;
    for (std::size_t i = 0; i < configs.size(); ++i) {
        if (int(i % std::size_t(ranks)) != rank) continue;
        const EstimatorConfig& c = configs[i];
        RenderSettings settings = settings_from_scene(scene.render);
        for (const auto& [name, value] : c.options) apply_render_option(settings, name, value);
        const std::string options = describe_options(c.options);
        std::fprintf(stderr, "clpath: %s%s (%s): %s\n", rank_prefix().c_str(), c.name.c_str(), c.description.c_str(),
                     options.c_str());
        ConvergenceSeries s{c.name, c.description, options, {}};
        try {
            s.points = measure_convergence(ctx, scene, settings, reference, o.compare, limits, [&](const ConvergencePoint& p) {
                std::fprintf(stderr, "clpath:   %s%-14s spp=%-6llu %9.3f s  psnr=%7.3f dB  rmse=%.5g  relmse=%.5g\n",
                             rank_prefix().c_str(), c.name.c_str(), (unsigned long long)p.spp, p.seconds,
                             p.error.psnr, p.error.rmse, p.error.relmse);
            });
        } catch (const Error& e) {
            throw Error(o.scene + ": configuration '" + c.name + "': " + e.what());
        }
        series.push_back(std::move(s));
    }
    if (ranks > 1) {
        series = gather_series(series, configs, mpi_job());
        if (rank != 0) return 0;
    }

    const std::vector<double> levels{30, 35, 40};
    std::string md = "Convergence of `" + scene.name + "` at " + std::to_string(width) + "x" + std::to_string(height) +
                     " against `" + o.reference + "`" + (width == full_ref.width ? "" : " (reduced by block means)") +
                     ", on " + device.describe() +
                     (ranks > 1 ? " (configurations spread over " + std::to_string(ranks) + " MPI ranks)" : "") + ".";
    if (o.compare.mask_above > 0)
        md += " Pixels where the reference exceeds " + format_number(o.compare.mask_above) + " (and those within " +
              std::to_string(o.compare.mask_grow) + " pixels of them) are left out.";
    if (o.compare.clamp > 0) md += " Both images clamped to " + format_number(o.compare.clamp) + ".";
    md += " PSNR with peak 1 (linear radiance); times are render time (launches) to each point; efficiency is "
          "1/(MSE x time) at each configuration's last point, relative to the first row.\n\n";
    md += convergence_markdown(series, levels);
    std::printf("%s", md.c_str());
    if (!o.csv.empty()) write_text_file(o.csv, convergence_csv(scene.name, series));
    if (!o.md.empty()) write_text_file(o.md, md);
    return 0;
}

}  // namespace

Command add_bench_convergence_command(CLI::App& bench) {
    auto o = std::make_shared<ConvergenceArgs>();
    CLI::App* cmd = bench.add_subcommand(
        "convergence", "Error against a reference image at 1, 2, 4, ... spp for each estimator configuration");
    cmd->add_option("scene", o->scene, scene_argument_help())->required();
    cmd->add_option("--reference,-r", o->reference,
                    "Reference image (.exr or .pfm, linear) of the scene, at the render size or an integer multiple")
        ->required()
        ->check(CLI::ExistingFile);
    std::string names;
    for (const auto& n : estimator_config_names()) names += (names.empty() ? "" : ", ") + n;
    cmd->add_option("--configs", o->configs, "Configurations to run, comma-separated (default: all of " + names + ")")
        ->delimiter(',')
        ->check(CLI::IsMember(estimator_config_names()));
    cmd->add_option("--max-spp", o->max_spp, "Largest samples per pixel (a power of two is measured; default 1024, quick 16)")
        ->check(whole_number(1, std::uint64_t(1) << 31));
    cmd->add_option("--time-cap", o->time_cap, "Per configuration: start no doubling that would end past S seconds")
        ->check(real_number(0, 1e9, true));
    cmd->add_option("--width", o->width, "Render width (default: the reference's; it must be a multiple)")
        ->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Render height (default: from the width and the reference's aspect)")
        ->check(whole_number(1, 16384));
    cmd->add_option("--csv", o->csv, "Write every point as CSV here");
    cmd->add_option("--md", o->md, "Write the Markdown table here");
    cmd->add_option("--mask-above", o->compare.mask_above,
                    "Leave out pixels where the reference exceeds V in any channel (directly seen emitters)")
        ->check(real_number(0, 1e9, true));
    cmd->add_option("--mask-grow", o->compare.mask_grow,
                    "Also leave out pixels within N pixels of a masked one (an emitter's partly covered edge)")
        ->check(whole_number(0, 64));
    cmd->add_option("--clamp", o->compare.clamp, "Clamp both images to [0, V] before comparing")
        ->check(real_number(0, 1e9, true));
    cmd->add_flag("--quick", o->quick, "Seconds, for CI: about 32 pixels wide, up to 16 spp");
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    return [o] { return run_convergence(*o); };
}

}  // namespace clpath
