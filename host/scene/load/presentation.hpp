#pragma once
// The default presentation of a bare mesh (an OBJ, or any model file that
// brings no camera and no lights): a camera framing its bounding box from the
// three-quarter view that shows most of its surface, a neutral ground under
// it that takes its shadow, and a sky with a sun (a constant-colour
// environment and a directional light). docs/scene-format.md describes it;
// every part can be overridden from the command line.
#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath {

struct PresentationOptions {
    bool ground = true;
    // Replaces the sky and the sun: a colour or an HDR image lights the mesh alone.
    std::optional<Environment> environment;
};

// What the presentation adds, fixed so that documentation and tests can name it.
namespace presentation {
constexpr float kVerticalFov = 40;            // degrees
constexpr float kGroundAlbedo = 0.5f;         // neutral grey
constexpr float kGroundHalfSize = 50;         // in bounding-sphere radii: wide enough to reach the horizon
const glm::vec3 kSkyRadiance{0.30f, 0.34f, 0.40f};  // a pale blue sky
const glm::vec3 kSunIrradiance{2.3f, 2.2f, 2.0f};   // W/m^2: lit ground about 2.5x its shadow
constexpr float kSunElevation = 50;           // degrees above the horizon
constexpr float kSunAzimuthOffset = 50;       // degrees, from the camera's side: shadows fall aside
}  // namespace presentation

// The unit direction from the model's centre towards the camera: among
// three-quarter views (azimuths every 15 degrees, elevations 15 to 45 degrees)
// the one whose sight of the surface, sum of area * max(0, n . d) over the
// triangles, is largest; near-ties go to a view from the front right, above.
glm::vec3 presentation_view_direction(const Scene& scene);

// Camera, ground, sky and sun as above, added to a scene that holds only
// meshes. When the mesh emits light itself, only the camera (and the ground
// when asked for) is added: it brings its own lighting.
void present_bare_mesh(Scene& scene, const PresentationOptions& options);

// The same for a model file that may bring its own camera or lights (a glTF
// file): with keep_camera its camera stays (the sun is then placed beside
// that camera's view); punctual lights count like emitting materials, so a
// model with either gets no ground, sky or sun unless options.environment
// replaces its lighting.
void present_model(Scene& scene, const PresentationOptions& options, bool keep_camera);

}  // namespace clpath
