// 'clpath view': options of the interactive viewer (host/viewer). In a build
// without the viewer (configured with -DCLPATH_WITH_VIEWER=OFF, e.g. where GLFW is missing) the command still
// exists and says so.
#include <memory>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "render/renderer.hpp"
#include "render/settings.hpp"
#include "util/error.hpp"
// The options struct is plain C++; only run_viewer() needs the viewer built in.
#include "viewer/viewer.hpp"

namespace clpath {

Command add_view_command(CLI::App& app) {
    auto o = std::make_shared<ViewerOptions>();
    CLI::App* cmd = app.add_subcommand("view", "Open a window that refines the image while you fly through the scene");
    cmd->add_option("scene", o->scene, scene_argument_help())
        ->capture_default_str();
    cmd->add_option("--device,-d", o->device, "OpenCL device: index or name substring (see 'clpath devices')")
        ->check(non_empty(kDeviceChoices));
    cmd->add_option("--width", o->width, "Window width (default: the scene's image width)")->check(whole_number(1, 16384));
    cmd->add_option("--height", o->height, "Window height (default: the scene's image height)")
        ->check(whole_number(1, 16384));
    cmd->add_option("--render-scale", o->render_scale,
                    "Render pixels per window pixel: below 1 for speed on a slow device")
        ->check(real_number(0.05, 4.0))
        ->capture_default_str();
    cmd->add_option("--frame-ms", o->frame_ms, "Rendering budget per frame, in milliseconds")
        ->check(real_number(1, 10000))
        ->capture_default_str();
    cmd->add_option("--max-spp", o->max_spp, "Stop refining at this many samples per pixel (default: never)")
        ->check(whole_number(1, kMaxSamplesPerPixel));
    cmd->add_option("--integrator,-i", o->integrator, "Integrator to start with (keys 1-7 switch)")
        ->check(CLI::IsMember(integrator_names()));
    cmd->add_option("--max-depth", o->max_depth, "Maximum bounces (default: the scene's, else 16)")
        ->check(whole_number(0, 1024));
    cmd->add_option("--seed", o->seed, "Random seed (default: the scene's, else 0)")->check(whole_number(0, 4294967295u));
    cmd->add_option("--exposure", o->exposure, "Exposure to start with, a multiplier (keys - and = change it)")
        ->check(real_number(0, 1000000, true))
        ->capture_default_str();
    cmd->add_option("--screenshot-dir", o->screenshot_dir, "Folder for screenshots (key P) and window captures (F12)")
        ->capture_default_str();
    cmd->add_option("--frames", o->frames, "Exit after this many frames (for tests and captures)")
        ->check(whole_number(1, 1000000000));
    cmd->add_option("--script", o->script,
                    "Scripted input, one command a line: wait N, wait-spp N, wait-denoised, key K, hold K N, "
                    "drag DX DY, click X Y, scroll S, screenshot, capture FILE, resize W H, camera, quit")
        ->check(CLI::ExistingFile);
    cmd->add_option("--state-log", o->state_log, "Write the viewer's state as JSON Lines, one line a frame");
    cmd->add_flag("--hide-hud", o->hide_hud, "Start with the heads-up display hidden (key H toggles it)");
    return [o] {
#ifdef CLPATH_WITH_VIEWER
        return run_viewer(*o);
#else
        throw Error("this clpath was built without the viewer (configure with -DCLPATH_WITH_VIEWER=ON, "
                    "which needs GLFW and Dear ImGui)");
        return 1;
#endif
    };
}

}  // namespace clpath
