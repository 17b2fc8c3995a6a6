#pragma once
// Which parts of the kernels a render needs. The OpenCL program is compiled
// with exactly these (as CLP_HAS_* definitions, the integrator and the maximum
// depth), so a Cornell box of diffuse walls and one area light carries no
// glass, environment or delta-light code. One cached binary per feature set.
#include <array>
#include <cstdint>
#include <string>

#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct KernelFeatures {
    std::array<bool, CLP_MAT_KIND_COUNT> materials{};  // indexed by CLP_MAT_*
    bool emission = false;         // some surface emits
    bool triangle_lights = false;  // emissive triangles are light-sampled (path integrator)
    bool delta_lights = false;     // point, spot, directional lights
    bool environment = false;      // rays that leave the scene see an environment
    bool environment_map = false;  // ... given by an image
    bool normals = false;          // interpolated shading normals
    bool flat_accel = false;       // traverse the flat list of object boxes, not the BVH (CLP_ACCEL_FLAT)
    bool uniform_hemisphere = false;  // diffuse bounces sample the hemisphere uniformly
    bool textures = false;       // some material maps a texture (CLP_HAS_TEXTURES)
    bool vertex_colors = false;  // per-vertex colours multiply base colours (CLP_HAS_VERTEX_COLORS)
    bool alpha = false;          // MASK or BLEND coverage is tested in traversal (CLP_HAS_ALPHA)
    // With alpha: the scene's attribute layout (CLP_SCENE_UVS, _TANGENTS,
    // _COLORS), which the coverage test in traversal reads as a constant
    // (CLP_ALPHA_ATTRIBUTES, kernels/scene_data.cl).
    std::uint32_t alpha_attributes = 0;
    bool clearcoat = false;      // a glTF material has a clear coat (CLP_HAS_CLEARCOAT)
    bool transmission = false;   // a glTF material transmits (CLP_HAS_TRANSMISSION)
    bool instances = false;      // meshes placed by instances: the two-level walk (CLP_HAS_INSTANCES)
    bool light_bvh = false;      // next-event estimation picks lights by the light BVH (CLP_LIGHT_BVH)
    std::uint32_t integrator = CLP_INTEGRATOR_PATH;
    std::uint32_t max_depth = 16;

    bool operator==(const KernelFeatures&) const = default;
};

// What a scene holds, independent of how it is rendered.
struct SceneFeatures {
    std::array<bool, CLP_MAT_KIND_COUNT> materials{};  // kinds some triangle uses
    bool emission = false, lights = false, environment = false, environment_map = false, normals = false;
    bool textures = false, vertex_colors = false, alpha = false;
    bool clearcoat = false, transmission = false;  // glTF layers (KHR_materials_clearcoat, _transmission)
    bool instances = false;  // some mesh is placed by instances (Scene::instances)
    // Lights that power alone picks badly: at least kManyFiniteLights finite
    // lights (emissive triangles, point and spot lights; the triangles of the
    // flat arrays: emitters are never instanced) spread over a box at least
    // kManyLightsSpread of the scene's diagonal, so that they differ in
    // distance and direction as seen from the points they light (a small
    // emissive sphere of 80 triangles is one lamp to most of the scene).
    // LightSampler::Auto then picks by the light BVH. Finite lights beside an
    // environment are not enough: the light BVH gives the environment a fixed
    // share, better where it is unseen (a closed room), worse where it lights
    // the scene (benchmarks/results/pocl-epyc-2core/light-sampler, docs/light-bvh.md).
    bool many_lights = false;
    std::uint32_t attributes = 0;  // CLP_SCENE_UVS, _TANGENTS, _COLORS: the per-triangle attributes it has
};
SceneFeatures scene_features(const Scene& scene);
constexpr std::size_t kManyFiniteLights = 16;
constexpr float kManyLightsSpread = 1.0f / 16;

// Whether a render of a scene with these features picks lights by the light
// BVH: the path integrator with lights, and LightSampler::Bvh, or Auto (or
// CLPATH_LIGHT_SAMPLER) choosing it. Throws clpath::Error for a bad
// CLPATH_LIGHT_SAMPLER.
bool uses_light_bvh(const SceneFeatures& scene, const RenderSettings& settings);

// What this scene, rendered with these settings, uses. With settings.all_features
// every feature is on, whatever the scene holds, except alpha, which follows
// the scene (it changes traversal's arguments, kernels/textures.cl), and the
// glTF layers, which follow it too (they change the BSDF's arguments and
// cost a shading kernel registers that no other scene should pay).
KernelFeatures kernel_features(const SceneFeatures& scene, const RenderSettings& settings);

// "-cl-std=CL1.2 -DCLP_HAS_MAT_DIFFUSE -DCLP_HAS_EMISSION ... -DCLP_INTEGRATOR=0u -DCLP_MAX_DEPTH=16u"
std::string build_options(const KernelFeatures& features);

}  // namespace clpath
