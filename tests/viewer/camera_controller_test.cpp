// The fly camera and the camera snippet: pure logic, no window.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/camera_snippet.hpp"

using namespace clpath;
using namespace clpath::viewer;

namespace {

Camera start_camera() {
    Camera c;
    c.eye = {0, 0.31f, -1.2f};
    c.target = {0, 0.31f, -0.2f};
    c.up = {0, 1, 0};
    c.vfov_degrees = 53.13f;
    c.width = 640;
    c.height = 480;
    return c;
}

bool same(const Camera& a, const Camera& b) {
    return a.eye == b.eye && a.target == b.target && a.up == b.up && a.vfov_degrees == b.vfov_degrees &&
           a.width == b.width && a.height == b.height;
}

glm::vec3 forward(const Camera& c) { return glm::normalize(c.target - c.eye); }

}  // namespace

TEST(ViewerCamera, StillCameraIsTheSceneCameraExactly) {
    FlyCamera fly(start_camera(), 1.0f);
    EXPECT_FALSE(fly.update({}, 0.1f, 0.01f));
    Camera expect = start_camera();
    expect.width = 64;
    expect.height = 48;
    EXPECT_TRUE(same(fly.camera(64, 48), expect));
}

TEST(ViewerCamera, ForwardKeyMovesAlongTheViewBySpeedTimesTime) {
    FlyCamera fly(start_camera(), 2.0f);
    MotionInput in;
    in.move = {0, 0, 1};
    EXPECT_TRUE(fly.update(in, 0.25f, 0.01f));
    const Camera c = fly.camera(640, 480);
    EXPECT_NEAR(c.eye.z, -1.2f + 0.5f, 1e-6f);
    EXPECT_NEAR(c.eye.x, 0.0f, 1e-6f);
    EXPECT_NEAR(c.eye.y, 0.31f, 1e-6f);
    EXPECT_NEAR(glm::length(c.target - c.eye), 1.0f, 1e-5f);  // the scene's eye-target distance is kept
}

TEST(ViewerCamera, StrafeAndRiseFollowRightAndWorldUp) {
    FlyCamera fly(start_camera(), 1.0f);
    MotionInput in;
    in.move = {1, 1, 0};  // D and E
    fly.update(in, 1.0f, 0.01f);
    const Camera c = fly.camera(640, 480);
    // Right is forward x up: looking down +z with +y up, right is -x.
    const glm::vec3 right = glm::normalize(glm::cross(forward(start_camera()), glm::vec3(0, 1, 0)));
    EXPECT_NEAR(c.eye.x, right.x, 1e-6f);
    EXPECT_NEAR(c.eye.y, 0.31f + 1.0f, 1e-6f);
}

TEST(ViewerCamera, DragRightTurnsRightAndDragUpLooksUp) {
    const glm::vec3 right = glm::normalize(glm::cross(forward(start_camera()), glm::vec3(0, 1, 0)));
    FlyCamera fly(start_camera(), 1.0f);
    MotionInput in;
    in.drag = {10, 0};
    fly.update(in, 0.0f, 0.01f);
    EXPECT_GT(glm::dot(forward(fly.camera(640, 480)), right), 0.09f);  // sin(0.1 rad) = 0.0998
    fly.reset();
    in.drag = {0, -10};  // window y grows downwards
    fly.update(in, 0.0f, 0.01f);
    EXPECT_NEAR(forward(fly.camera(640, 480)).y, std::sin(0.1f), 1e-5f);
}

TEST(ViewerCamera, PitchStopsShortOfStraightUpSoTheCameraStaysValid) {
    FlyCamera fly(start_camera(), 1.0f);
    MotionInput in;
    in.drag = {0, -100000};
    fly.update(in, 0.0f, 0.01f);
    const Camera c = fly.camera(640, 480);
    EXPECT_LT(forward(c).y, 1.0f);
    EXPECT_NO_THROW(camera_data(c));
    in.drag = {0, 200000};
    fly.update(in, 0.0f, 0.01f);
    EXPECT_GT(forward(fly.camera(640, 480)).y, -1.0f);
    EXPECT_NO_THROW(camera_data(fly.camera(640, 480)));
}

TEST(ViewerCamera, ResetReturnsToTheSceneCameraAndScrollScalesSpeed) {
    FlyCamera fly(start_camera(), 1.0f);
    MotionInput in;
    in.move = {0, 0, 1};
    in.drag = {5, 5};
    in.scroll = 2;
    fly.update(in, 0.5f, 0.01f);
    EXPECT_NEAR(fly.speed(), FlyCamera::kSpeedStep * FlyCamera::kSpeedStep, 1e-6f);
    EXPECT_FALSE(same(fly.camera(640, 480), start_camera()));
    fly.reset();
    EXPECT_TRUE(same(fly.camera(640, 480), start_camera()));
    MotionInput scroll_only;
    scroll_only.scroll = 1;
    EXPECT_FALSE(fly.update(scroll_only, 0.1f, 0.01f)) << "a speed change alone does not move the camera";
}

TEST(ViewerCamera, SnippetIsJsonThatReadsBackToTheSameCamera) {
    Camera c = start_camera();
    c.eye = {0.1f, 1.0f / 3.0f, -2.5e-7f};
    const auto j = nlohmann::json::parse(camera_snippet(c));
    const auto& cam = j.at("camera");
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(cam.at("eye")[i].get<float>(), c.eye[i]);
        EXPECT_EQ(cam.at("target")[i].get<float>(), c.target[i]);
        EXPECT_EQ(cam.at("up")[i].get<float>(), c.up[i]);
    }
    EXPECT_EQ(cam.at("vfov").get<float>(), c.vfov_degrees);
    EXPECT_EQ(cam.at("resolution")[0].get<int>(), 640);
    EXPECT_EQ(cam.at("resolution")[1].get<int>(), 480);
}
