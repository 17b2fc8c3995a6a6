#pragma once
// The thesis renderer's debug view: the BVH's boxes as wireframes over the
// image, drawn with GL lines through the same projection the kernels' camera
// uses, coloured by depth.
#include <glm/glm.hpp>

#include "scene/scene.hpp"
#include "viewer/bvh_boxes.hpp"

namespace clpath::viewer {

class BvhOverlay {
public:
    BvhOverlay();  // compiles its shader; throws clpath::Error with the log on failure
    ~BvhOverlay();
    BvhOverlay(const BvhOverlay&) = delete;
    BvhOverlay& operator=(const BvhOverlay&) = delete;

    void set_boxes(const std::vector<LevelBox>& boxes);
    // near_far: clip distances, from the scene's size.
    void draw(const Camera& camera, glm::ivec4 viewport, glm::vec2 near_far) const;

private:
    unsigned program_ = 0, vao_ = 0, vbo_ = 0;
    int mvp_location_ = -1;
    int vertex_count_ = 0;
};

// The view-projection matrix matching camera_data(): right = forward x up,
// vertical field of view, aspect from the resolution.
glm::mat4 view_projection(const Camera& camera, glm::vec2 near_far);

}  // namespace clpath::viewer
