#pragma once
// glTF 2.0 files (.gltf with external or data-URI buffers, .glb), read
// through tinygltf and checked here: every accessor, buffer view and index is
// bounds-checked, and a fault names the file and the glTF path at fault
// ("model.gltf: meshes[3].primitives[0].attributes.TEXCOORD_0: ...").
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/load/load_options.hpp"
#include "scene/scene.hpp"
#include "util/error.hpp"

namespace clpath {

// One mesh primitive, already turned into triangle corners (3 per triangle;
// strips and fans converted), in the mesh's own space.
struct GltfPrimitive {
    std::string path;                 // "meshes[0].primitives[1]", for messages
    std::vector<glm::vec3> vertices;
    std::vector<glm::vec3> normals;   // empty, or 3 per triangle
    std::vector<glm::vec2> uvs;       // TEXCOORD_0: empty, or 3 per triangle
    std::vector<glm::vec4> tangents;  // empty, or 3 per triangle
    std::vector<glm::vec4> colors;    // COLOR_0 (RGB gets alpha 1): empty, or 3 per triangle
    int material = -1;                // index into GltfModel::materials; -1: the default material
    std::string warning;              // for GltfModel::warnings: what reading it dropped
};

// A mesh placed by the node hierarchy.
struct GltfInstance {
    std::size_t mesh = 0;
    glm::mat4 world{1};
    std::string node;  // "nodes[4]", for messages
};

struct GltfMaterial {
    std::string name;
    SceneMaterial material;  // CLP_MAT_GLTF; texture slots index GltfModel::textures
    // KHR_texture_transform of its textures, applied to the texture
    // coordinates of the primitives that use it (GltfPrimitive::uvs).
    std::optional<glm::mat3> uv_transform;
};

struct GltfModel {
    std::vector<std::vector<GltfPrimitive>> meshes;
    std::vector<GltfInstance> instances;
    std::vector<GltfMaterial> materials;
    std::vector<Texture> textures;
    std::vector<PunctualLight> lights;  // KHR_lights_punctual, placed
    std::optional<Camera> camera;       // the chosen perspective camera, placed
    std::vector<std::string> warnings;
    std::size_t triangle_count() const;
};

// options.gltf_camera names no camera that the file's nodes place: the
// message lists the cameras there are. Its own type so that a program can
// tell the user which of its options was wrong.
struct UnknownGltfCamera : Error {
    using Error::Error;
};

// Reads `file` through options.read_file (and the files it names relative to
// its folder); textures through options.decode_texture; the camera chosen by
// options.gltf_camera. Throws clpath::Error naming the file and glTF path.
GltfModel load_gltf(const std::string& file, const LoadOptions& options);

// True for the file names load_gltf reads (.gltf, .glb, any case).
bool is_gltf_file(const std::string& file);

}  // namespace clpath
