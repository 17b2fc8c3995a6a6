#pragma once
// Scripted input for the viewer, for tests and for reproducible captures.
// One command a line; '#' starts a comment:
//   wait N            let N frames pass
//   wait-spp N        wait until the image has N samples per pixel
//   wait-denoised     with denoising on (key N), wait until the window shows the
//                     current estimate denoised (at least until the next frame
//                     after other commands); at once when denoising is off or
//                     cannot run
//   key K             press and release key K ("w", "1", "tab", "[", "f12", ...)
//   hold K N          hold key K down for N frames (movement keys)
//   drag DX DY        one mouse drag of DX, DY window pixels (y down)
//   scroll S          scroll S wheel steps
//   click X Y         a left click at window pixel (X, Y) (y down): focus there
//   screenshot [NAME] what key P does: PNG + linear EXR of the current mean;
//                     NAME replaces the file name's stem
//   capture FILE      write this frame's window, heads-up display included, as a
//                     PNG; later commands run from the next frame on
//   resize W H        resize the window
//   camera            print the camera as a scene-file snippet
//   quit              close the viewer
#include <cstdint>
#include <string>
#include <vector>

namespace clpath::viewer {

struct ScriptCommand {
    enum class Kind { Wait, WaitSpp, WaitDenoised, Key, Hold, Drag, Scroll, Click, Screenshot, Capture, Resize, Camera, Quit };
    Kind kind;
    std::string text;  // key name or file
    double a = 0, b = 0;
    int line = 0;
};

// Throws clpath::Error naming source:line for an unknown command, a missing
// or malformed argument, or an unknown key.
std::vector<ScriptCommand> parse_view_script(const std::string& text, const std::string& source);
std::vector<ScriptCommand> load_view_script(const std::string& path);

// Steps through a script one frame at a time.
class ScriptRunner {
public:
    explicit ScriptRunner(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}

    struct Step {
        std::vector<ScriptCommand> commands;  // to carry out this frame, in order
        std::vector<std::string> held;        // keys held down this frame
    };
    // Called once before each frame with the image's current samples per pixel
    // and whether the shown image has caught up with it (viewer/view_denoiser.hpp).
    Step next_frame(std::uint64_t spp, bool denoise_caught_up = true);
    bool finished() const { return next_ == commands_.size() && hold_frames_ == 0; }
    // The line of the command the script is at (0 when finished).
    int current_line() const { return next_ < commands_.size() ? commands_[next_].line : 0; }

private:
    std::vector<ScriptCommand> commands_;
    std::size_t next_ = 0;
    long wait_frames_ = 0;  // frames still to let pass for the current wait
    bool waiting_ = false;
    std::string hold_key_;
    long hold_frames_ = 0;
};

}  // namespace clpath::viewer
