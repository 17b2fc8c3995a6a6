#pragma once
// The heads-up display, through Dear ImGui: what the renderer is doing and
// how fast, and the keys.
#include <cstdint>
#include <string>

struct GLFWwindow;

namespace clpath::viewer {

struct HudState {
    std::string scene, device, integrator, display_path, error;
    std::uint64_t spp = 0, max_spp = 0;
    std::size_t triangles = 0;
    int width = 0, height = 0;
    double ms_per_frame = 0, msamples_per_s = 0, mrays_per_s = 0;
    float exposure = 1, speed = 0;
    int bvh_depth = 0, bvh_levels = 0;  // bvh_depth 0: overlay off
    float aperture_radius = 0, focus_distance = 0;  // aperture 0: a pinhole
    std::string denoise;          // the denoise row: off, on with its time, what it waits for, or why it cannot
    bool denoise_problem = false;  // shown as an error
};

class Hud {
public:
    // Installs ImGui's GLFW callbacks, which chain to the window's own.
    explicit Hud(GLFWwindow* window);
    ~Hud();
    Hud(const Hud&) = delete;
    Hud& operator=(const Hud&) = delete;

    void draw(const HudState& state);  // a whole ImGui frame, over what is drawn
    bool wants_mouse() const;          // the cursor is over the panel
    void toggle() { visible_ = !visible_; }
    bool visible() const { return visible_; }

private:
    bool visible_ = true;
};

}  // namespace clpath::viewer
