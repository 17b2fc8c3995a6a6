#pragma once
// Puts placed geometry into a Scene: applies the object's transform to
// vertices and normals, drops degenerate triangles (and counts them for one
// warning), keeps Scene::normals either empty or complete, and enforces the
// triangle budget before anything large is made.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath {

// Per-corner attributes beside positions and normals: each null/empty or 3 per
// triangle (see Scene::uvs, tangents, colors).
struct VertexAttributes {
    const std::vector<glm::vec2>* uvs = nullptr;
    const std::vector<glm::vec4>* tangents = nullptr;
    const std::vector<glm::vec4>* colors = nullptr;
};

class SceneBuilder {
public:
    SceneBuilder(Scene& scene, std::size_t max_triangles)
        : scene_(scene), max_triangles_(max_triangles), with_uvs_(!scene.uvs.empty()),
          with_tangents_(!scene.tangents.empty()), with_colors_(!scene.colors.empty()) {}

    // Fails, naming `label`, when `triangles` more would exceed the budget;
    // callers ask before they generate a big shape.
    void reserve(std::size_t triangles, const std::string& label) const;

    // Triangles (3 vertices each) placed by m. normals: empty (flat), or 3 per
    // triangle, where a zero vector means "none here" and the triangle is then
    // shaded flat. materials: one per triangle, or a single one for all.
    void add(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals, const glm::mat4& m,
             const std::vector<std::uint32_t>& materials, const std::string& label,
             const VertexAttributes& attributes = {});

    // Appends the degenerate-triangle warning, if any were dropped.
    void finish();

    std::size_t dropped() const { return dropped_total_; }

private:
    Scene& scene_;
    std::size_t max_triangles_;
    bool with_normals_ = false;
    bool with_uvs_, with_tangents_, with_colors_;
    std::size_t dropped_total_ = 0;
    std::vector<std::pair<std::string, std::size_t>> dropped_;  // per label, in order
};

// The flat normal of a triangle: unit (v1 - v0) x (v2 - v0).
glm::vec3 flat_normal(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2);

// Zero area (repeated or collinear vertices) or a non-finite vertex.
bool is_degenerate(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2);

}  // namespace clpath
