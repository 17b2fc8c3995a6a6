// clpath export SCENE OUT.json: the scene as OBJ + MTL + a clpath scene file,
// for rendering references with another renderer (Blender Cycles); with
// --format mitsuba, a Mitsuba 3 scene dictionary and one OBJ per material;
// with --format embree (OUT.ecs), OBJ + MTL + a command script for Embree's
// example path tracer.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "scene/export/embree_export.hpp"
#include "scene/export/mitsuba_export.hpp"
#include "scene/export/obj_export.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"
#include "util/text_file.hpp"

namespace clpath {
namespace {

struct ExportArgs {
    std::string scene, out;
    int width = 0, height = 0;
    std::optional<std::uint32_t> max_depth;
    std::string format = "obj";
};

// --format mitsuba: the meshes and texel files first, the scene dictionary that names them last.
int run_mitsuba_export(const ExportArgs& o, const Scene& scene) {
    namespace fs = std::filesystem;
    const fs::path json = o.out;
    MitsubaExport e;
    try {
        e = export_mitsuba_scene(scene, json.stem().string(), o.scene);
    } catch (const Error& err) {
        throw Error(o.scene + ": cannot export: " + err.what());
    }
    std::vector<fs::path> written;
    std::error_code ec;
    try {
        auto files = e.meshes;
        files.insert(files.end(), e.textures.begin(), e.textures.end());
        for (const auto& [name, text] : files) {
            const fs::path p = json.parent_path() / name;
            check_text_output_path(p.string());
            write_text_file(p.string(), text);
            written.push_back(p);
        }
        write_text_file(json.string(), e.json);
    } catch (const Error&) {
        for (const auto& p : written) fs::remove(p, ec);
        throw;
    }
    const std::string textures = e.textures.empty() ? "" : " and " + std::to_string(e.textures.size()) + " texture files";
    std::printf("wrote %s and %zu meshes%s: Mitsuba 3, %zu triangles, %dx%d, max depth %u\n", json.string().c_str(),
                e.meshes.size(), textures.c_str(), scene.triangle_count(), scene.camera.width, scene.camera.height,
                scene.render.max_depth);
    return 0;
}

int run_export(const ExportArgs& o) {
    namespace fs = std::filesystem;
    const fs::path json = o.out;
    const bool embree = o.format == "embree";
    if (embree && json.extension() != ".ecs")
        throw UsageError("output " + o.out + ": --format embree writes an Embree command script, NAME.ecs (the OBJ and "
                         "MTL go beside it)");
    if (!embree && json.extension() != ".json")
        throw UsageError("output " + o.out + ": must end in .json (the OBJ and MTL go beside it)");
    const std::string stem = json.stem().string();
    const fs::path obj = fs::path(json).replace_extension(".obj"), mtl = fs::path(json).replace_extension(".mtl");
    // The folder is made (as render makes out/) only once the export has
    // succeeded; what can be checked before is checked here.
    const fs::path folder = json.parent_path();
    std::error_code ec;
    if (!folder.empty() && fs::exists(folder, ec) && !fs::is_directory(folder, ec))
        throw UsageError("output " + o.out + ": " + folder.string() + " is a file, not a folder");
    if (fs::is_directory(folder.empty() ? fs::path(".") : folder, ec))
        for (const auto& p : {json, obj, mtl}) check_text_output_path(p.string());

    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    // The exported formats hold triangles: every instance's copy goes out
    // flattened (at most 50 million triangles; more is refused by name).
    if (!scene.instances.empty()) scene = flatten_instances(scene, 50'000'000);
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    if (o.max_depth) scene.render.max_depth = *o.max_depth;
    if (o.format == "mitsuba") {
        if (!folder.empty() && !fs::is_directory(folder, ec)) fs::create_directories(folder, ec);
        return run_mitsuba_export(o, scene);
    }
    ObjExport e;
    try {
        if (embree) {
            EmbreeExport x = export_embree_scene(scene, stem, o.scene);
            e.obj = std::move(x.obj);
            e.mtl = std::move(x.mtl);
            e.json = std::move(x.ecs);  // written where the scene file would be: the path ends in .ecs
        } else {
            e = export_obj_scene(scene, stem, o.scene);
        }
    } catch (const Error& err) {
        throw Error(o.scene + ": cannot export: " + err.what());
    }
    if (!folder.empty() && !fs::is_directory(folder, ec)) {
        fs::create_directories(folder, ec);
        if (ec) throw Error("output " + o.out + ": cannot create the folder " + folder.string() + ": " + ec.message());
    }
    // The scene file last: it is what names the other two. A failure removes
    // what this run wrote.
    try {
        write_text_file(obj.string(), e.obj);
        write_text_file(mtl.string(), e.mtl);
        write_text_file(json.string(), e.json);
    } catch (const Error&) {
        for (const auto& p : {obj, mtl}) fs::remove(p, ec);
        throw;
    }
    std::printf("wrote %s, %s, %s: %zu triangles, %dx%d, max depth %u\n", json.string().c_str(), obj.string().c_str(),
                mtl.string().c_str(), scene.triangle_count(), scene.camera.width, scene.camera.height,
                scene.render.max_depth);
    return 0;
}

}  // namespace

Command add_export_command(CLI::App& app) {
    auto o = std::make_shared<ExportArgs>();
    CLI::App* cmd = app.add_subcommand(
        "export", "Write a scene as OBJ + MTL + a scene file (for Cycles references)");
    cmd->footer(
        "--format obj (the default) exports diffuse materials, emitters (one- or two-sided), flat-shaded triangles\n"
        "and a constant-colour environment, and refuses, naming the first one met: mirror, conductor (glossy) and\n"
        "dielectric (glass) materials, smooth shading normals, punctual lights (point, spot, directional: so a\n"
        "bare mesh's default sun too) and environment images. --format mitsuba exports every material and light.\n"
        "--format embree (OUT ends in .ecs) writes OBJ + MTL and an Embree command script for Embree's example\n"
        "path tracer (`pathtracer -c OUT.ecs`, Debian's embree-tools): diffuse surfaces and point lights only.\n"
        "The output folder is created if missing.");
    cmd->add_option("scene", o->scene, scene_argument_help())->required();
    cmd->add_option("out", o->out, "Output scene file NAME.json; NAME.obj and NAME.mtl are written beside it")
        ->required();
    cmd->add_option("--width", o->width, "Image width (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Image height (default: the scene's)")->check(whole_number(1, 16384));
    cmd->add_option("--max-depth", o->max_depth, "Maximum bounces to record (default: the scene's)")
        ->check(whole_number(0, 1024));
    cmd->add_option("--format", o->format,
                    "obj: OBJ + MTL + scene file, diffuse and emissive surfaces only (Cycles); mitsuba: a Mitsuba 3 "
                    "scene dictionary (JSON) and one OBJ per material, every material and light (Mitsuba references); "
                    "embree: OBJ + MTL + an Embree command script (.ecs) for Embree's pathtracer example")
        ->check(CLI::IsMember({"obj", "mitsuba", "embree"}));
    return [o] { return run_export(*o); };
}

}  // namespace clpath
