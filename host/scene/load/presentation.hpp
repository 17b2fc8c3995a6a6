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
constexpr float kMaxElevation = 30;           // degrees: the view never looks down more steeply
constexpr float kFramingMargin = 0.9f;        // the bounding sphere fills 90 % of the frame's shorter side
// A model's own emitters and lights count as its lighting when they give at
// least this fraction of the irradiance the sky and sun above would: a
// quarter (two photographic stops) still shows the model at a normal exposure.
constexpr float kOwnLightEnough = 0.25f;
}  // namespace presentation

// The irradiance (luminance, W/m^2) the sky and sun above give a horizontal surface.
float presentation_irradiance();

// The unit direction from the model's centre towards the camera: among
// three-quarter views (azimuths every 15 degrees, elevations 10 to 30 degrees)
// the one whose sight of the surface, sum of area * max(0, n . d) over the
// triangles, is largest; near-ties go to a view from the front right, above.
glm::vec3 presentation_view_direction(const Scene& scene);

// Camera, ground, sky and sun as above, added to a scene that holds only
// meshes. The camera frames the model's bounding sphere (kFramingMargin). When
// the mesh's own emitters give at least kOwnLightEnough of the sky and sun's
// irradiance, only the camera is added: it brings its own lighting; weaker
// emitters keep shining, with the sky, sun and ground added beside them.
// Which was chosen, and why, is added to scene.notes.
void present_bare_mesh(Scene& scene, const PresentationOptions& options);

// The same for a model file that may bring its own camera or lights (a glTF
// file): with keep_camera its camera stays (the sun is then placed beside
// that camera's view); punctual lights count like emitting materials, by the
// irradiance they bring the model, and options.environment replaces the
// presentation's lighting.
void present_model(Scene& scene, const PresentationOptions& options, bool keep_camera);

}  // namespace clpath
