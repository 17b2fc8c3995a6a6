#pragma once
// A scene made ready for the kernels, on the host and once: validated, its
// acceleration structure built, its light table and environment distribution
// made. It names no device, so one PreparedScene can be uploaded to several
// (DeviceScene) without building anything again.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/accel.hpp"
#include "bvh/bvh.hpp"
#include "bvh/instances.hpp"
#include "render/environment_map.hpp"
#include "render/kernel_features.hpp"
#include "render/light_bvh.hpp"
#include "render/light_table.hpp"
#include "render/surface_buffers.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"
#include "shared_structs.h"

namespace clpath {

// What a render needs to know of a scene once its arrays are on a device:
// small, copied into every DeviceScene.
// The light BVH as the kernels' frame parameters describe it (FrameParams.lbvh_*).
struct LightBvhSummary {
    bool built = false;  // prepared (the settings may pick lights by it); else no buffer holds it
    glm::vec3 origin{0.0f}, scale{0.0f};
    std::uint32_t node_count = 0, infinite_count = 0;
    int depth = 0;
    double build_ms = 0;
};

struct SceneSummary {
    std::string name;
    Accel accel = Accel::Bvh;
    SceneFeatures features;
    BvhStats bvh_stats;
    std::size_t triangle_count = 0;
    std::size_t light_count = 0;                // entries of the light table
    std::uint32_t environment_light = CLP_NO_LIGHT;  // the environment's entry in it
    int environment_width = 0, environment_height = 0;  // 0 x 0: no image
    glm::vec3 environment_color{0};
    float environment_scale = 1;
    float environment_rotation = 0;  // radians about +y
    float diagonal = 1;              // of the bounding box; 1 for a degenerate one
    std::uint32_t attr_stride = 0;   // FrameParams.attr_stride (render/surface_buffers.hpp)
    std::uint32_t surface_flags = 0; // CLP_SCENE_UVS, _TANGENTS, _COLORS, _MATERIAL_EXT
    bool instanced = false;          // the two-level BVH (features.instances); instance_stats says what it holds
    TwoLevelStats instance_stats;
    LightBvhSummary light_bvh;
};

struct PreparedScene {
    SceneSummary summary;
    Camera camera;  // the scene's own
    // The structure the kernels traverse; its leaf-ordered triangles carry their light's index.
    // For an instanced scene (summary.instanced): no binary nodes, the
    // triangles of every bottom level, and the nodes in instanced_nodes.
    Bvh accel;
    std::vector<Bvh4Node128> instanced_nodes;  // top level, instance records, bottom levels (bvh/instances.hpp)
    std::vector<std::uint32_t> triangle_material;  // per scene triangle, then each instanced mesh's (from its first_prim)
    std::vector<Material> materials;
    // Parallel to materials when the scene maps a texture or cuts out by
    // alpha (summary.surface_flags has CLP_SCENE_MATERIAL_EXT); else empty,
    // and the device holds one zero record.
    std::vector<MaterialExt> material_ext;
    std::vector<glm::vec3> normals;  // empty, or three per scene triangle
    std::vector<Light> lights;
    std::vector<AliasEntry> light_alias;  // parallel to lights
    // Built where the settings pick lights by it (summary.light_bvh.built).
    LightBvh light_bvh;
    EnvironmentMap environment;
    SurfaceBuffers surface;  // texture coordinates, tangents, colours and textures
};

// Builds the structure of settings.accel with settings.bvh (the other settings
// change nothing here). Throws clpath::Error when the scene is invalid or its
// environment image cannot be read.
std::shared_ptr<const PreparedScene> prepare_scene(const Scene& scene, const RenderSettings& settings);

// The two-level BVH of a scene that places meshes by instances, as the
// kernels walk it: the flat triangles (if any) as one mesh placed once under
// the identity, then the scene's meshes, each mesh's triangles' .prim after
// the flat ones'. Throws clpath::Error as build_two_level does.
TwoLevelBvh scene_two_level(const Scene& scene, const BvhBuildOptions& options);

// The node buffer the kernels traverse, as bytes: device_nodes of the
// structure in the program's layout (render/kernel_programs.hpp,
// node_layout), or the two-level nodes of an instanced scene (always 4-wide).
std::vector<unsigned char> scene_node_bytes(const PreparedScene& scene, NodeLayout layout);

}  // namespace clpath
