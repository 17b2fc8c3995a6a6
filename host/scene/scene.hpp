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
    // Thin lens: the aperture's radius in world units (0: a pinhole, everything
    // sharp) and the distance along the view direction of the plane in focus
    // (0: the target's distance).
    float aperture_radius = 0.0f;
    float focus_distance = 0.0f;
    bool has_lens() const { return aperture_radius > 0.0f; }
    // The plane in focus: focus_distance, or the target's distance along the view.
    float resolved_focus_distance() const;
    // Above 0: an orthographic camera whose view is this tall (half the
    // height, in scene units; the width follows the image's aspect), and
    // vfov_degrees is not used.
    float ortho_half_height = 0;
};

// The ray basis the kernels read (kernels/camera.cl). Right is forward x up,
// row 0 is the top of the image. Throws clpath::Error for a degenerate camera
// (eye == target, up parallel to the view direction, fov outside (0, 180),
// a negative or non-finite aperture or focus distance).
CameraData camera_data(const Camera& camera);

// A delta light, reached only through next-event estimation.
struct PunctualLight {
    enum class Type { Point, Spot, Directional };
    Type type = Type::Point;
    glm::vec3 position{0};       // point, spot
    glm::vec3 direction{0, -1, 0};  // spot axis; for directional, the way the light travels
    glm::vec3 intensity{1};      // W/sr (point, spot); irradiance W/m^2 (directional)
    float spot_inner_degrees = 30, spot_outer_degrees = 45;  // half-angles; smooth falloff between
};

// What a ray that leaves the scene sees: a constant colour, or an
// equirectangular (latitude-longitude) HDR image times a scale.
struct Environment {
    glm::vec3 color{0};  // radiance when there is no image
    std::string image;   // path to an equirectangular image (read through OpenImageIO); empty: none
    float scale = 1;     // multiplies the image
    float rotation_degrees = 0;  // about +y
    bool importance_sampled = true;
    bool emits() const { return !image.empty() || color.x > 0 || color.y > 0 || color.z > 0; }
};

// Render settings a scene file may carry; the command line overrides them.
struct SceneRenderDefaults {
    std::uint32_t spp = 64;
    std::uint32_t max_depth = 16;
    std::string russian_roulette = "throughput";  // none | throughput | depth
    std::string integrator = "path";              // see scene/render_names.hpp
    std::uint32_t seed = 0;
    float ao_distance = 0;                        // 0: a tenth of the scene's bounding-box diagonal
    double noise_target = 0;                      // adaptive sampling's target (render/adaptive.hpp); 0: off
    std::string light_sampler = "auto";           // auto | power | bvh (render/settings.hpp LightSampler)
};

// A decoded texture image with the addressing its file asks for. 8-bit files
// keep their bytes (RGBA8, as stored: sRGB decoding is the reader's, per use);
// float files (EXR, HDR) keep linear RGBA floats.
struct Texture {
    std::string name;  // for messages: the file or glTF path it came from
    int width = 0, height = 0;
    bool is_float = false;
    std::vector<std::uint8_t> rgba8;  // 4 per texel, row 0 at the top
    std::vector<float> rgba32;        // 4 per texel, when is_float
    std::uint32_t wrap_s = CLP_WRAP_REPEAT, wrap_t = CLP_WRAP_REPEAT;
    bool nearest = false;
    std::size_t texel_bytes() const { return is_float ? rgba32.size() * sizeof(float) : rgba8.size(); }
};

// A material as a scene holds it: the record every kernel reads (Material)
// and its texture maps and coverage (MaterialExt), which only kernels with
// textures or alpha cut-outs read. The renderer uploads the two parts as two
// buffers (render/prepared_scene.hpp), so scenes without those features keep
// the material table they had before them.
struct SceneMaterial : Material, MaterialExt {};

// A mesh placed by instances (Scene::instances): its triangles are stored
// once, in its own object space, and are not in the scene's flat arrays.
// Emissive meshes are never instanced (the loaders place them flattened), so
// the light table holds every emitter as before. Its vertex attributes are
// as the Scene's below (each empty or three per triangle), tangents in
// object space: the kernels move them with the instance (textures.cl).
struct InstancedMesh {
    std::string name;                                // for messages: the file or label it came from
    std::vector<glm::vec3> vertices;                 // three per triangle, object space
    std::vector<std::uint32_t> triangle_material;    // one per triangle
    std::vector<glm::vec3> normals;                  // empty (flat), or three per triangle; zero: none there
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec4> colors;
    std::size_t triangle_count() const { return triangle_material.size(); }
};

// One placement of an InstancedMesh: world = object_to_world * object. Any
// invertible affine map: translation, rotation, non-uniform scale, mirroring.
struct MeshInstance {
    std::uint32_t mesh = 0;            // index in Scene::meshes
    glm::mat4 object_to_world{1.0f};   // affine (last row 0 0 0 1)
};

struct Scene {
    std::string name;
    // Three vertices per triangle; a triangle's front face is the side from
    // which (v0, v1, v2) appear counter-clockwise: normal (v1-v0) x (v2-v0).
    std::vector<glm::vec3> vertices;
    std::vector<std::uint32_t> triangle_material;  // one per triangle
    // The object (shape or mesh, as the scene defines it) of each triangle, one
    // per triangle: the flat acceleration structure boxes each object (bvh/flat.hpp).
    std::vector<std::uint32_t> triangle_object;
    std::vector<SceneMaterial> materials;
    std::vector<std::string> material_names;  // parallel to materials
    // Empty (flat shading), or three per triangle, parallel to vertices.
    std::vector<glm::vec3> normals;
    // Each empty, or three per triangle, parallel to vertices: texture
    // coordinates (TEXCOORD_0, v down as in glTF), tangents (xyz, w the
    // bitangent's sign; a zero xyz means "derive one"), and vertex colours
    // (RGBA, multiplying the base colour; 1 where a mesh has none).
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec4> colors;
    // Meshes placed by instances, each instance a copy in the world; empty
    // for a scene whose every triangle is in the arrays above.
    std::vector<InstancedMesh> meshes;
    std::vector<MeshInstance> instances;
    std::vector<Texture> textures;  // MaterialExt::texture indexes these
    std::vector<PunctualLight> lights;
    Environment environment;
    Camera camera;
    SceneRenderDefaults render;
    // What loading dropped, ignored or fell back on (degenerate triangles,
    // texture maps, ...), one line each; the program that loaded it prints them.
    std::vector<std::string> warnings;
    // What loading decided on the user's behalf and why (the default
    // presentation's lighting), one line each; printed unless output is quiet.
    std::vector<std::string> notes;

    // The triangles of the flat arrays (instanced meshes not counted).
    std::size_t triangle_count() const { return triangle_material.size(); }
    // The triangles in the world: the flat ones plus every instance's copy.
    std::size_t placed_triangle_count() const;
    // Adds a material and returns its index; names must be unique.
    std::uint32_t add_material(const std::string& name, const SceneMaterial& m);
    // Appends triangles (3 vertices each) with one material, as a new object.
    void add_triangles(const std::vector<glm::vec3>& tris, std::uint32_t material);
    // The id the next object gets (ids are consecutive from 0).
    std::uint32_t next_object_id() const { return triangle_object.empty() ? 0u : triangle_object.back() + 1u; }
    // Anything that puts light in: an emissive triangle, a punctual light, an environment.
    bool has_emitter() const;
    // The vertex attributes any triangle has, flat or instanced
    // (CLP_SCENE_UVS, _TANGENTS, _COLORS): where one has them, every
    // triangle carries the record, with the defaults above where it has none.
    std::uint32_t attribute_flags() const;
};

// The scene with every instance's copy added to the flat arrays (and none
// left instanced), as the loaders place a transformed mesh: vertices moved,
// two corners swapped for a mirroring transform (the front face stays the
// outside), normals through the inverse transpose. What exporters and the
// renderer's comparisons of instancing against flattening use. Throws
// clpath::Error when the copies would exceed max_triangles.
Scene flatten_instances(const Scene& scene, std::size_t max_triangles = std::size_t(1) << 31);

// A vertex tangent (xyz, w the bitangent's sign) moved by a transform's
// linear part: tangents are directions on the surface, so they move with
// it (not its inverse transpose) and are made unit; a mirroring transform
// flips the bitangent's sign. A zero or non-finite result is the zero
// tangent ("derive one"). What SceneBuilder and flatten_instances give.
glm::vec4 moved_tangent(const glm::mat3& linear, bool mirrors, glm::vec4 tangent);

// The float[3] fields of the shared structs, to and from glm.
inline void store3(float* dst, glm::vec3 v) {
    dst[0] = v.x;
    dst[1] = v.y;
    dst[2] = v.z;
}
inline glm::vec3 load3(const float* p) { return {p[0], p[1], p[2]}; }

// A material kind's name in the one table (CLP_MATERIAL_KINDS,
// kernels/shared_structs.h): "diffuse", "mirror", ...; throws clpath::Error
// for a kind the table lacks.
const char* material_kind_name(std::uint32_t kind);
// Whether scene files name the kind as a material "type" (the table's third column).
bool material_kind_in_scene_files(std::uint32_t kind);

// Some channel of the material's emission is positive.
inline bool emits(const Material& m) { return m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0; }

// Every field at its neutral value: no textures, opaque, ior 1.5.
SceneMaterial base_material();
// The glTF metallic-roughness material (CLP_MAT_GLTF) without textures.
SceneMaterial gltf_material(glm::vec3 base_color, float metallic, float roughness);
SceneMaterial diffuse(glm::vec3 albedo);
SceneMaterial mirror(glm::vec3 tint = glm::vec3(1));
SceneMaterial conductor(glm::vec3 f0, float roughness);
SceneMaterial dielectric(float ior, float roughness = 0, glm::vec3 tint = glm::vec3(1));
// A one-sided emitter unless two_sided; albedo 0: it does not reflect.
SceneMaterial emitter(glm::vec3 radiance, bool two_sided = false, glm::vec3 albedo = glm::vec3(0));

}  // namespace clpath
