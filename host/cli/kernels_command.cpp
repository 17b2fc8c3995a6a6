// clpath kernels: the OpenCL programs clpath builds, listed, written out as
// sources with their build options (--dump), or compiled offline for NVIDIA
// and AMD GPU targets with the registers, stack and spills of every kernel
// (--report); --check makes the report the portability gate.
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/report_files.hpp"
#include "cli/commands.hpp"
#include "cli/kernel_variant_option.hpp"
#include "cli/option_checks.hpp"
#include "render/kernel_report.hpp"
#include "render/settings.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// ctest's SKIP_RETURN_CODE (and automake's): what --check exits with when a
// target's tools are missing, so the gate never passes without checking.
constexpr int kSkipped = 77;

struct KernelsOptions {
    std::vector<std::string> scenes, targets;
    std::string dump, csv, md, work, cache, code = "gpu", kernels_dir, extra_options;
    bool list = false, report = false, check = false, covering = false;
    int jobs = 0;
};

std::vector<ProgramSpec> programs_for(const KernelsOptions& o) {
    const KernelCode code = parse_kernel_code(o.code);
    std::vector<NamedSceneFeatures> scenes;
    std::set<std::string> names;
    for (const auto& spec : o.scenes) {
        const Scene scene = load_scene(spec);
        std::string name = std::filesystem::path(spec).stem().string();
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '-';
        for (std::string base = name; !names.insert(name).second;) name = base + "-" + std::to_string(names.size());
        scenes.push_back({name, scene_features(scene), settings_from_scene(scene.render)});
    }
    if (scenes.empty() || o.covering) return covering_programs(scenes, code);
    std::vector<ProgramSpec> out;
    std::set<std::string> seen;
    for (const auto& s : scenes)
        for (auto& p : scene_programs(s, code))
            if (seen.insert(p.options + "|" + p.roots.front()).second) out.push_back(std::move(p));
    return out;
}

int run_kernels(const KernelsOptions& o) {
    if (!o.dump.empty() + o.report + o.list != 1)
        throw UsageError("give one of --list, --dump DIR and --report");
    if (o.check && !o.report) throw UsageError("--check goes with --report");
    for (const auto& t : o.targets) {
        bool known = false;
        for (const auto& k : gpu_target_names()) known = known || k == t;
        if (!known) throw UsageError("--targets: unknown target '" + t + "' (known: sm_90, gfx90a, gfx1100)");
    }
    if (!o.csv.empty()) check_report_path(o.csv, "--csv");
    if (!o.md.empty()) check_report_path(o.md, "--md");
    const std::vector<ProgramSpec> programs = programs_for(o);
    const KernelVariant variant = read_kernel_variant(o.kernels_dir, o.extra_options, "--kernels");

    if (o.list) {
        for (const auto& p : programs)
            std::printf("%s\t%s\t(%s)\n", p.name.c_str(), p.options.c_str(), p.covers.c_str());
        return 0;
    }
    if (!o.dump.empty()) {
        write_program_dump(programs, o.dump, variant);
        std::printf("%zu programs written to %s (NAME.cl, NAME.options, programs.tsv)\n", programs.size(),
                    o.dump.c_str());
        return 0;
    }

    const OfflineToolchain tools = find_offline_toolchain();
    const std::vector<std::string> targets = o.targets.empty() ? gpu_target_names() : o.targets;
    std::string skipped;
    for (const auto& t : targets)
        if (const std::string m = missing_tools(tools, t); !m.empty())
            skipped += "  " + t + ": missing " + m + "\n";
    std::fprintf(stderr, "clpath: toolchain:\n%s", toolchain_versions(tools).c_str());
    if (!skipped.empty()) std::fprintf(stderr, "clpath: targets not compiled:\n%s", skipped.c_str());

    CompileRun run;
    run.jobs = o.jobs > 0 ? o.jobs : int(std::max(1u, std::thread::hardware_concurrency()));
    run.cache_dir = o.cache;
    run.variant = variant;
    const bool temporary = o.work.empty();
    run.work_dir = temporary ? (std::filesystem::temp_directory_path() /
                                ("clpath-kernels-" + std::to_string(::getpid())))
                                   .string()
                             : o.work;
    std::size_t done = 0;
    std::size_t usable = 0;
    for (const auto& t : targets) usable += missing_tools(tools, t).empty();
    const std::size_t total = programs.size() * usable;
    run.on_done = [&](const ProgramCompile& c) {
        ++done;
        std::fprintf(stderr, "clpath: [%zu/%zu] %s %s: %s", done, total, c.program->name.c_str(),
                     c.result.target.c_str(), c.result.ok ? "ok" : "FAILED");
        if (c.result.from_cache)
            std::fprintf(stderr, " (cached)\n");
        else
            std::fprintf(stderr, " (%.1f s)\n", c.result.seconds);
    };
    std::vector<ProgramCompile> compiles;
    try {
        compiles = compile_programs(programs, targets, tools, run);
    } catch (...) {
        if (temporary) std::filesystem::remove_all(run.work_dir);
        throw;
    }
    if (temporary) std::filesystem::remove_all(run.work_dir);

    std::printf("%-28s %-22s %-8s %9s %6s %9s %6s\n", "program", "kernel", "target", "registers", "sgprs",
                "stack B", "spills");
    int failed = 0;
    for (const auto& c : compiles) {
        if (!c.result.ok) {
            ++failed;
            std::printf("%-28s %-22s %-8s FAILED\n", c.program->name.c_str(), "", c.result.target.c_str());
            continue;
        }
        for (const auto& k : c.result.kernels)
            std::printf("%-28s %-22s %-8s %9d %6d %9d %6d\n", c.program->name.c_str(), k.kernel.c_str(),
                        c.result.target.c_str(), k.registers, k.sgprs, k.stack_bytes, k.spill_bytes);
    }
    for (const auto& c : compiles)
        if (!c.result.ok)
            std::fprintf(stderr, "clpath: %s for %s (%s):\n%s\n", c.program->name.c_str(), c.result.target.c_str(),
                         c.program->options.c_str(), c.result.log.c_str());
    if (!o.csv.empty()) write_report_file(o.csv, resources_csv(compiles));
    if (!o.md.empty()) write_report_file(o.md, resources_markdown(compiles));
    const auto over = budget_violations(compiles), open = budget_shortfalls(compiles);
    for (const auto& v : open) std::fprintf(stderr, "clpath: over budget, open: %s\n", v.c_str());
    for (const auto& v : over) std::fprintf(stderr, "clpath: over budget: %s\n", v.c_str());
    std::printf("%zu programs, %zu compiles: %d failed, %zu over budget, %zu open shortfalls (over budget, "
                "within the figures held)%s\n", programs.size(), compiles.size(), failed, over.size(), open.size(),
                skipped.empty() ? "" : "; some targets not compiled (tools missing)");
    if (!o.check) return failed ? 1 : 0;
    if (failed || !over.empty()) return 1;
    if (!skipped.empty()) {
        std::printf("SKIPPED: the gate did not run for every target:\n%s", skipped.c_str());
        return kSkipped;
    }
    return 0;
}

}  // namespace

Command add_kernels_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "kernels",
        "The OpenCL programs clpath builds: list them, write their sources and build options (--dump), or "
        "compile them offline for NVIDIA sm_90 and AMD gfx90a/gfx1100 with each kernel's registers, stack and "
        "spills (--report)");
    auto o = std::make_shared<KernelsOptions>();
    cmd->add_option("scenes", o->scenes,
                    "Scenes whose programs to take (" + scene_argument_help() +
                        "); none: the set that covers every program a scene can select");
    cmd->add_flag("--covering", o->covering, "With scenes: the covering set too");
    cmd->add_flag("--list", o->list, "Print each program's name, build options and what selects it");
    cmd->add_option("--dump", o->dump, "Write DIR/NAME.cl (source, includes in place), DIR/NAME.options and "
                                       "DIR/programs.tsv");
    cmd->add_flag("--report", o->report, "Compile every program for the GPU targets and print each kernel's "
                                         "registers, stack/private bytes and spills");
    cmd->add_flag("--check", o->check, "With --report: exit 1 on any failed compile, unresolved symbol or kernel "
                                       "over its budget, 77 when a target's tools are missing");
    cmd->add_option("--code", o->code, "Which code of the kernels: gpu (as built for GPU devices, -DCLP_TARGET_GPU) or cpu")
        ->check(CLI::IsMember({"gpu", "cpu"}));
    cmd->add_option("--targets", o->targets, "sm_90, gfx90a, gfx1100 (default: all)")->delimiter(',');
    cmd->add_option("--jobs", o->jobs, "Compiles at once (default: one per core)")->check(whole_number(1, 1024));
    cmd->add_option("--kernels", o->kernels_dir, "Kernel files (*.cl, *.h) in this folder replace clpath's files "
                                                 "of the same names");
    cmd->add_option("--options", o->extra_options, "Build options added to every program's, e.g. "
                                                   "--options=\"-DNAME\"");
    cmd->add_option("--csv", o->csv, "Write the resource table as CSV");
    cmd->add_option("--md", o->md, "Write the resource table as Markdown");
    cmd->add_option("--work", o->work, "Keep each compile's files under this folder (default: a temporary one)");
    cmd->add_option("--cache", o->cache, "Reuse results stored in this folder for the same source, options, "
                                         "target and tools");
    return [o] { return run_kernels(*o); };
}

}  // namespace clpath
