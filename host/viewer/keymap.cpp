#include "viewer/keymap.hpp"

#include <map>

#include "shared_structs.h"

namespace clpath::viewer {

std::optional<KeyAction> action_for_key(const std::string& key) {
    static const std::map<std::string, KeyAction> table = {
        {"escape", {Action::Quit}},
        {"1", {Action::SetIntegrator, CLP_INTEGRATOR_PATH}},
        {"2", {Action::SetIntegrator, CLP_INTEGRATOR_PATH_BSDF}},
        {"3", {Action::SetIntegrator, CLP_INTEGRATOR_AO}},
        {"4", {Action::SetIntegrator, CLP_INTEGRATOR_NORMALS}},
        {"5", {Action::SetIntegrator, CLP_INTEGRATOR_DEPTH}},
        {"6", {Action::SetIntegrator, CLP_INTEGRATOR_ALBEDO}},
        {"7", {Action::SetIntegrator, CLP_INTEGRATOR_HEATMAP}},
        {"tab", {Action::NextIntegrator}},
        {"b", {Action::ToggleBvhOverlay}},
        {"]", {Action::BvhDeeper}},
        {"[", {Action::BvhShallower}},
        {"=", {Action::ExposureUp}},
        {"-", {Action::ExposureDown}},
        {"p", {Action::Screenshot}},
        {"f12", {Action::CaptureWindow}},
        {"c", {Action::PrintCamera}},
        {"r", {Action::ResetCamera}},
        {"h", {Action::ToggleHud}},
        {"n", {Action::ToggleDenoise}},
    };
    auto it = table.find(key);
    if (it == table.end()) return std::nullopt;
    return it->second;
}

bool is_movement_key(const std::string& key) {
    return key == "w" || key == "a" || key == "s" || key == "d" || key == "q" || key == "e";
}

const std::vector<std::pair<std::string, std::string>>& key_help() {
    static const std::vector<std::pair<std::string, std::string>> help = {
        {"W A S D / Q E", "move / down, up"},
        {"left drag", "look around"},
        {"left click", "focus the lens on the surface there"},
        {"scroll", "movement speed"},
        {"1-7, Tab", "path, path-bsdf, ao, normals, depth, albedo, heatmap"},
        {"B, [ ]", "BVH boxes on/off, depth"},
        {"- =", "exposure down / up (half a stop)"},
        {"N", "denoise the shown image (Open Image Denoise) on / off"},
        {"P", "screenshot: PNG + linear EXR (and .denoised twins with N on)"},
        {"F12", "capture the window"},
        {"C", "print the camera as JSON"},
        {"R", "back to the scene's camera"},
        {"H", "hide / show this panel"},
        {"Esc", "quit"},
    };
    return help;
}

}  // namespace clpath::viewer
