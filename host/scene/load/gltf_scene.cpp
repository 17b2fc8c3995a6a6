#include "scene/load/gltf_scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "scene/load/presentation.hpp"
#include "scene/load/scene_instances.hpp"
#include "util/error.hpp"

namespace clpath {

void add_gltf(Scene& scene, SceneBuilder& builder, const GltfModel& model, const glm::mat4& place,
              const std::string& file, bool smooth, const std::function<std::uint32_t(int)>& material_override) {
    const int texture_base = int(scene.textures.size());
    bool textures_added = false;
    // Materials are added when a triangle first uses them, so that an
    // overridden or unused one costs nothing on the device.
    std::vector<std::int64_t> index(model.materials.size() + 1, -1);  // [0]: the default material
    auto scene_material = [&](int gm) -> std::uint32_t {
        if (material_override) {
            const std::uint32_t o = material_override(gm);
            if (o != std::numeric_limits<std::uint32_t>::max()) return o;
        }
        auto& slot = index[std::size_t(gm + 1)];
        if (slot >= 0) return std::uint32_t(slot);
        if (!textures_added) {
            scene.textures.insert(scene.textures.end(), model.textures.begin(), model.textures.end());
            textures_added = true;
        }
        // The specification's default material: white, fully metallic, fully rough.
        SceneMaterial m = gm < 0 ? gltf_material(glm::vec3(1), 1, 1) : model.materials[std::size_t(gm)].material;
        for (int& t : m.texture)
            if (t != CLP_NO_TEXTURE) t += texture_base;
        std::string name = file + ":" + (gm < 0 ? "(default)" : model.materials[std::size_t(gm)].name);
        if (std::find(scene.material_names.begin(), scene.material_names.end(), name) != scene.material_names.end())
            name = file + ":materials[" + std::to_string(gm) + "]";
        slot = scene.add_material(name, m);
        return std::uint32_t(slot);
    };
    static const std::vector<glm::vec3> kNone;
    // A primitive of a mesh that several nodes place is stored once and
    // placed by instances, with its attributes, unless it could not be
    // instanced anyway (it emits: flattened_because); then, as every
    // primitive placed once, it is added flattened, in node order.
    std::vector<std::vector<glm::mat4>> placements(model.meshes.size());
    for (const GltfInstance& inst : model.instances) placements[inst.mesh].push_back(place * inst.world);
    auto shared = [&](std::size_t mesh, std::uint32_t mat) {
        return placements[mesh].size() > 1 && flattened_because(scene, {mat}).empty();
    };
    for (const GltfInstance& inst : model.instances)
        for (const GltfPrimitive& p : model.meshes[inst.mesh]) {
            if (p.vertices.empty()) continue;
            const std::uint32_t mat = scene_material(p.material);
            if (shared(inst.mesh, mat)) continue;
            VertexAttributes attr{&p.uvs, &p.tangents, &p.colors};
            builder.add(p.vertices, smooth ? p.normals : kNone, place * inst.world, {mat}, file + ": " + inst.node + " " + p.path,
                        attr);
        }
    std::size_t not_shared = 0;  // primitives several nodes place that could not be instanced
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
        for (const GltfPrimitive& p : model.meshes[m]) {
            if (p.vertices.empty()) continue;
            const std::uint32_t mat = scene_material(p.material);
            if (!shared(m, mat)) {
                not_shared += placements[m].size() > 1;
                continue;
            }
            const VertexAttributes attr{&p.uvs, &p.tangents, &p.colors};
            place_mesh_instances(scene, builder,
                                 file + ": " + p.path + " (placed by " + std::to_string(placements[m].size()) + " nodes)",
                                 p.vertices, smooth ? p.normals : kNone, {mat}, glm::mat4(1), placements[m], attr);
        }
    if (not_shared)
        scene.notes.push_back(file + ": " + std::to_string(not_shared) +
                              " mesh primitives placed by several nodes are placed flattened, not instanced (they emit, "
                              "and the light table lists flattened emitters only)");
    const glm::mat3 linear(place);
    for (PunctualLight l : model.lights) {
        l.position = glm::vec3(place * glm::vec4(l.position, 1));
        const glm::vec3 d = linear * l.direction;
        if (glm::length(d) > 0) l.direction = glm::normalize(d);
        scene.lights.push_back(l);
    }
}

Scene gltf_scene(const std::string& file, const LoadOptions& options) {
    const GltfModel model = load_gltf(file, options);
    Scene s;
    s.name = std::filesystem::path(file).stem().string();
    s.warnings = model.warnings;
    if (model.triangle_count() == 0) {
        // What was skipped (points, lines) is why, when anything was.
        std::string why;
        for (const auto& w : model.warnings) why += "; " + w;
        throw Error(file + ": the file places no triangles (an empty scene)" + why);
    }
    SceneBuilder builder(s, options.max_triangles);
    add_gltf(s, builder, model, glm::mat4(1), file);
    builder.finish();
    if (s.placed_triangle_count() == 0) throw Error(file + ": every triangle is degenerate (an empty scene)");
    // Framed, grounded and lit as a bare OBJ is, keeping what the file brings.
    if (model.camera) s.camera = *model.camera;
    present_model(s, options.presentation, model.camera.has_value());
    return s;
}

}  // namespace clpath
