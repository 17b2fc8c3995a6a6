#pragma once
// The fly camera: keys move the eye, a mouse drag turns the view, scroll sets
// the speed. Pure state, no window: the viewer feeds it one frame's input and
// restarts the accumulation whenever update() reports a change.
#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath::viewer {

struct MotionInput {
    glm::vec3 move{0};     // x: right, y: up (world), z: forward; each -1, 0 or 1
    glm::vec2 drag{0};     // mouse movement with the button down, window pixels, y down
    float scroll = 0;      // wheel steps; each one scales the speed by kSpeedStep
};

class FlyCamera {
public:
    static constexpr float kSpeedStep = 1.25f;

    // speed: world units per second. The scene camera's up stays the world's
    // up, so the horizon never rolls.
    FlyCamera(const Camera& start, float speed);

    // Applies one frame of input over dt seconds; radians_per_pixel turns a
    // drag into an angle. Returns whether the camera changed.
    bool update(const MotionInput& in, float dt, float radians_per_pixel);

    // The current camera at a resolution. Until the first move this is the
    // scene's camera exactly, so a still view matches 'clpath render' bit for bit.
    Camera camera(int width, int height) const;

    // The thin lens's plane in focus (a click on a surface); the view is unchanged.
    void set_focus_distance(float distance);

    void reset();  // back to the scene's camera (the speed is kept)
    float speed() const { return speed_; }
    bool moved() const { return moved_; }

private:
    Camera start_;
    glm::vec3 world_up_;
    glm::vec3 eye_, forward_;
    float distance_;  // eye to target, kept so a printed camera has the scene's scale
    float speed_;
    float focus_distance_;  // the scene's until a click sets it
    bool moved_ = false;
};

}  // namespace clpath::viewer
