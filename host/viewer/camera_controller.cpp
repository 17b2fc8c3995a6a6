#include "viewer/camera_controller.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace clpath::viewer {
namespace {

// Looking straight up or down would make up parallel to the view direction,
// which the camera rejects; stop a little short of it.
constexpr float kMinAngleToPole = 0.02f;  // radians

glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float angle) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

}  // namespace

FlyCamera::FlyCamera(const Camera& start, float speed) : start_(start), speed_(speed) { reset(); }

void FlyCamera::reset() {
    world_up_ = glm::normalize(start_.up);
    eye_ = start_.eye;
    distance_ = glm::length(start_.target - start_.eye);
    forward_ = (start_.target - start_.eye) / distance_;
    focus_distance_ = start_.focus_distance;
    moved_ = false;
}

void FlyCamera::set_focus_distance(float distance) { focus_distance_ = distance; }

bool FlyCamera::update(const MotionInput& in, float dt, float radians_per_pixel) {
    if (in.scroll != 0) speed_ *= std::pow(kSpeedStep, in.scroll);
    bool changed = false;
    if (in.drag.x != 0 || in.drag.y != 0) {
        // Dragging right turns right; dragging up looks up.
        glm::vec3 f = rotate(forward_, world_up_, -in.drag.x * radians_per_pixel);
        const glm::vec3 right = glm::normalize(glm::cross(f, world_up_));
        const float angle = std::acos(std::clamp(glm::dot(f, world_up_), -1.0f, 1.0f));  // 0: straight up
        const float pitch = std::clamp(-in.drag.y * radians_per_pixel, angle - glm::pi<float>() + kMinAngleToPole,
                                       angle - kMinAngleToPole);
        forward_ = glm::normalize(rotate(f, right, pitch));
        changed = true;
    }
    if (in.move != glm::vec3(0) && dt > 0) {
        const glm::vec3 right = glm::normalize(glm::cross(forward_, world_up_));
        eye_ += (right * in.move.x + world_up_ * in.move.y + forward_ * in.move.z) * (speed_ * dt);
        changed = true;
    }
    moved_ = moved_ || changed;
    return changed;
}

Camera FlyCamera::camera(int width, int height) const {
    Camera c = start_;
    if (moved_) {
        c.eye = eye_;
        c.target = eye_ + forward_ * distance_;
        c.up = world_up_;
    }
    c.width = width;
    c.height = height;
    c.focus_distance = focus_distance_;
    return c;
}

}  // namespace clpath::viewer
