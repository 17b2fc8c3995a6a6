// clpath: an OpenCL Monte Carlo path tracer. Subcommands: render, devices, compare, bench, export (and view with the viewer built in).
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "cli/commands.hpp"
#include "mpi/launch.hpp"
#include "scene/load/load_options.hpp"
#include "util/error.hpp"

namespace {
int run(int argc, char** argv);
}

int main(int argc, char** argv) {
    try {
        clpath::start_mpi_if_launched(&argc, &argv);
    } catch (const clpath::Error& e) {
        std::fprintf(stderr, "clpath: error: %s\n", e.what());
        return 2;
    }
    const int rc = run(argc, argv);
    clpath::finish_mpi(rc != 0);
    return rc;
}

namespace {

int run(int argc, char** argv) {
    CLI::App app{"clpath: an OpenCL Monte Carlo path tracer"};
    app.require_subcommand(1);
    std::map<CLI::App*, clpath::Command> commands;
    auto add = [&](clpath::Command (*adder)(CLI::App&)) {
        const std::size_t before = app.get_subcommands({}).size();
        clpath::Command run = adder(app);
        commands[app.get_subcommands({})[before]] = std::move(run);
    };
    std::string restrict_dir;
    app.add_option("--restrict-files", restrict_dir,
                   "Open no scene, mesh, material, texture or environment file outside this folder (after resolving "
                   "'..', links and absolute paths); default: $CLPATH_RESTRICT_FILES, else no restriction");
    app.fallthrough();  // before the commands, which inherit it: the option may follow a command's name
    add(clpath::add_render_command);
    add(clpath::add_devices_command);
    add(clpath::add_compare_command);
    add(clpath::add_view_command);
    add(clpath::add_bench_command);
    add(clpath::add_export_command);
    add(clpath::add_kernels_command);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version are not errors; CLI11 prints them.
        if (e.get_exit_code() == 0) return app.exit(e);
        // Every other message in the one form users and scripts can match.
        std::string where = "clpath";
        for (CLI::App* sub = &app; sub && !sub->get_subcommands().empty();) {
            sub = sub->get_subcommands().front();
            where += " " + sub->get_name();
        }
        std::fprintf(stderr, "clpath: error: %s\n(see '%s --help')\n", e.what(), where.c_str());
        return 2;
    }
    try {
        if (restrict_dir.empty())
            if (const char* env = std::getenv("CLPATH_RESTRICT_FILES")) restrict_dir = env;
        clpath::restrict_files_to(restrict_dir);
        for (auto* sub : app.get_subcommands())
            if (auto it = commands.find(sub); it != commands.end()) return it->second();
        return 2;
    } catch (const clpath::UsageError& e) {
        std::fprintf(stderr, "clpath: error: %s%s\n", clpath::rank_prefix().c_str(), e.what());
        return 2;
    } catch (const clpath::Error& e) {
        std::fprintf(stderr, "clpath: error: %s%s\n", clpath::rank_prefix().c_str(), e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "clpath: error: out of host memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "clpath: error: internal: %s\n", e.what());
        return 1;
    }
}

}  // namespace
