#pragma once
// 'clpath view': the progressive, interactive viewer.
//
// The render resolution follows the window's framebuffer (times
// render_scale): once a new size has settled the renderer gets a new film
// for it (the scene stays on the device); until then the last image is shown
// letterboxed.
#include <cstdint>
#include <optional>
#include <string>

namespace clpath {

struct ViewerOptions {
    std::string scene = "cornell";
    std::string device;
    int width = 0, height = 0;      // window size; 0: the scene camera's resolution
    float render_scale = 1;         // render pixels per framebuffer pixel
    double frame_ms = 33;           // rendering budget per frame
    std::uint64_t max_spp = 0;      // stop refining at this many samples per pixel; 0: never
    long frames = 0;                // exit after this many frames; 0: when closed
    std::string script;             // scripted input (viewer/view_script.hpp)
    std::string screenshot_dir = "out";
    std::string state_log;          // JSON Lines state record; empty: none
    float exposure = 1;
    bool hide_hud = false;
    std::optional<std::uint32_t> seed, max_depth;
    std::optional<std::string> integrator;
};

// Returns the exit status; throws clpath::Error for what stops it from
// starting (no display, no device, bad scene or script).
int run_viewer(const ViewerOptions& options);

}  // namespace clpath
