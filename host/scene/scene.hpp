#pragma once
// What the renderer renders: triangles with a material each, a material
// table and a camera. Built-in scenes and scene files only fill this struct.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared_structs.h"

namespace clpath {

struct Camera {
    glm::vec3 eye{0, 0, 0};
    glm::vec3 target{0, 0, 1};
    glm::vec3 up{0, 1, 0};
    float vfov_degrees = 45.0f;
    int width = 640, height = 480;
};

// The ray basis the kernels read (kernels/camera.cl). Right is forward x up,
// row 0 is the top of the image. Throws clpath::Error for a degenerate camera
// (eye == target, up parallel to the view direction, fov outside (0, 180)).
CameraData camera_data(const Camera& camera);

struct Scene {
    std::string name;
    // Three vertices per triangle; a triangle's front face is the side from
    // which (v0, v1, v2) appear counter-clockwise: normal (v1-v0) x (v2-v0).
    std::vector<glm::vec3> vertices;
    std::vector<std::uint32_t> triangle_material;  // one per triangle
    std::vector<Material> materials;
    std::vector<std::string> material_names;  // parallel to materials
    Camera camera;

    std::size_t triangle_count() const { return triangle_material.size(); }
    // Adds a material and returns its index; names must be unique.
    std::uint32_t add_material(const std::string& name, const Material& m);
    // Appends triangles (3 vertices each) with one material.
    void add_triangles(const std::vector<glm::vec3>& tris, std::uint32_t material);
    bool has_emitter() const;
};

Material diffuse(glm::vec3 albedo);
// A one-sided emitter unless two_sided; albedo 0: it does not reflect.
Material emitter(glm::vec3 radiance, bool two_sided = false, glm::vec3 albedo = glm::vec3(0));

}  // namespace clpath
