#pragma once
// What each key does in the viewer. Keys are named as a script writes them
// ("w", "1", "[", "tab", "escape"), so that scripted input and a real
// keyboard go through one table and a test of a script tests the keymap.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace clpath::viewer {

enum class Action {
    Quit,
    SetIntegrator,   // arg: CLP_INTEGRATOR_* value
    NextIntegrator,
    ToggleBvhOverlay,
    BvhDeeper,
    BvhShallower,
    ExposureUp,
    ExposureDown,
    Screenshot,      // PNG + EXR of the current mean
    CaptureWindow,   // PNG of the window, heads-up display included
    PrintCamera,
    ResetCamera,
    ToggleHud,
    ToggleDenoise,   // show the estimate denoised (Open Image Denoise); the estimate itself is unchanged
};

struct KeyAction {
    Action action;
    unsigned arg = 0;
};

// The action bound to a key press, if any (movement keys have none: they act while held).
std::optional<KeyAction> action_for_key(const std::string& key);

// The keys that move the camera while held: w a s d q e.
bool is_movement_key(const std::string& key);

// (keys, what they do), for the heads-up display's help.
const std::vector<std::pair<std::string, std::string>>& key_help();

}  // namespace clpath::viewer
