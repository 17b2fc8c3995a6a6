#include "render/prepared_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "util/error.hpp"

namespace clpath {
namespace {

void validate_instances(const Scene& s) {
    for (std::size_t k = 0; k < s.meshes.size(); ++k) {
        const InstancedMesh& m = s.meshes[k];
        const std::string what = "scene '" + s.name + "': instanced mesh '" + m.name + "'";
        if (m.triangle_count() == 0 || m.vertices.size() != 3 * m.triangle_count())
            throw Error("internal: " + what + " has no triangles or not three vertices each");
        if ((!m.normals.empty() && m.normals.size() != m.vertices.size()) ||
            (!m.uvs.empty() && m.uvs.size() != m.vertices.size()) ||
            (!m.tangents.empty() && m.tangents.size() != m.vertices.size()) ||
            (!m.colors.empty() && m.colors.size() != m.vertices.size()))
            throw Error("internal: " + what + " has normals, texture coordinates, tangents or colours for some vertices only");
        for (auto mi : m.triangle_material) {
            if (mi >= s.materials.size()) throw Error("internal: " + what + ": material index out of range");
            // The light table holds flattened emitters only.
            if (emits(s.materials[mi])) throw Error("internal: " + what + " emits: emissive meshes are placed flattened");
        }
    }
    for (std::size_t i = 0; i < s.instances.size(); ++i)
        if (s.instances[i].mesh >= s.meshes.size())
            throw Error("internal: scene '" + s.name + "': instance " + std::to_string(i) + " names no mesh");
}

void validate_scene(const Scene& s) {
    if (s.triangle_count() == 0 && s.instances.empty()) throw Error("scene '" + s.name + "' has no triangles");
    validate_instances(s);
    if (s.vertices.size() != s.triangle_count() * 3)
        throw Error("internal: scene '" + s.name + "' has " + std::to_string(s.vertices.size()) +
                    " vertices for " + std::to_string(s.triangle_count()) + " triangles");
    for (auto m : s.triangle_material)
        if (m >= s.materials.size()) throw Error("internal: triangle material index out of range");
    if (!s.normals.empty() && s.normals.size() != s.vertices.size())
        throw Error("internal: scene '" + s.name + "' has normals for some vertices only");
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        const SceneMaterial& m = s.materials[i];
        const std::string name = i < s.material_names.size() ? s.material_names[i] : std::to_string(i);
        if (m.kind >= CLP_MAT_KIND_COUNT) throw Error("material '" + name + "': unknown kind");
        if (m.kind == CLP_MAT_DIELECTRIC && !(m.ior > 0))
            throw Error("material '" + name + "': index of refraction must be positive");
        for (int t : m.texture)
            if (t != CLP_NO_TEXTURE && (t < 0 || std::size_t(t) >= s.textures.size()))
                throw Error("internal: material '" + name + "' names texture " + std::to_string(t));
    }
    if ((!s.uvs.empty() && s.uvs.size() != s.vertices.size()) ||
        (!s.tangents.empty() && s.tangents.size() != s.vertices.size()) ||
        (!s.colors.empty() && s.colors.size() != s.vertices.size()))
        throw Error("internal: scene '" + s.name + "' has texture coordinates, tangents or colours for some vertices only");
}

float bounding_diagonal(const Scene& s) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : s.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    std::vector<glm::vec3> mlo(s.meshes.size(), glm::vec3(INFINITY)), mhi(s.meshes.size(), glm::vec3(-INFINITY));
    for (std::size_t k = 0; k < s.meshes.size(); ++k)
        for (const auto& v : s.meshes[k].vertices) {
            mlo[k] = glm::min(mlo[k], v);
            mhi[k] = glm::max(mhi[k], v);
        }
    for (const auto& in : s.instances)
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 a = mlo[in.mesh], b = mhi[in.mesh];
            const glm::vec3 w(in.object_to_world * glm::vec4((c & 1) ? b.x : a.x, (c & 2) ? b.y : a.y, (c & 4) ? b.z : a.z, 1));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    const float d = glm::length(hi - lo);
    return d > 0 && std::isfinite(d) ? d : 1.0f;
}

// The two-level structure of an instanced scene: the flat triangles (if
// any) as one mesh under the identity, then the scene's meshes; each mesh's
// per-triangle data (materials, normals) after the flat ones, as its
// attributes are (pack_surface_buffers).
void prepare_instanced(const Scene& scene, const RenderSettings& settings, const std::vector<std::uint32_t>& light_of,
                       PreparedScene& p) {
    if (settings.accel != Accel::Bvh)
        throw Error("scene '" + scene.name + "' places meshes by instances, which only --accel bvh walks");
    TwoLevelBvh two = scene_two_level(scene, settings.bvh);
    for (auto& t : two.triangles) t.light = t.prim < light_of.size() ? light_of[t.prim] : CLP_NO_LIGHT;
    p.accel.triangles = std::move(two.triangles);
    p.instanced_nodes = std::move(two.nodes);
    BvhStats& st = p.accel.stats;
    st.build_ms = two.stats.top_build_ms + two.stats.bottom_build_ms;
    st.node_count = p.instanced_nodes.size();
    for (const auto& ms : two.mesh_stats) {
        st.leaf_count += ms.leaf_count;
        st.max_depth = std::max(st.max_depth, ms.max_depth);
    }
    p.summary.instanced = true;
    p.summary.instance_stats = two.stats;

    p.triangle_material = scene.triangle_material;
    for (const auto& m : scene.meshes)
        p.triangle_material.insert(p.triangle_material.end(), m.triangle_material.begin(), m.triangle_material.end());
    bool normals = !scene.normals.empty();
    for (const auto& m : scene.meshes) normals = normals || !m.normals.empty();
    if (normals) {  // a zero normal is "none here": that triangle is shaded flat (kernels/scene_data.cl)
        p.normals = scene.normals;
        p.normals.resize(scene.vertices.size(), glm::vec3(0));
        for (const auto& m : scene.meshes) {
            if (m.normals.empty()) p.normals.resize(p.normals.size() + m.vertices.size(), glm::vec3(0));
            else p.normals.insert(p.normals.end(), m.normals.begin(), m.normals.end());
        }
    }
}

}  // namespace

TwoLevelBvh scene_two_level(const Scene& scene, const BvhBuildOptions& options) {
    std::vector<const std::vector<glm::vec3>*> meshes;
    std::vector<std::uint32_t> first_prim;
    std::vector<InstanceInput> instances;
    const bool flat = scene.triangle_count() > 0;
    if (flat) {
        meshes.push_back(&scene.vertices);
        first_prim.push_back(0);
        instances.push_back({0, glm::mat4(1.0f)});
    }
    std::size_t prims = scene.triangle_count();
    for (const auto& m : scene.meshes) {
        if (prims + m.triangle_count() > 0xffffffffull)
            throw Error("scene '" + scene.name + "': more distinct triangles than 32-bit indices address");
        meshes.push_back(&m.vertices);
        first_prim.push_back(std::uint32_t(prims));
        prims += m.triangle_count();
    }
    for (const auto& in : scene.instances) instances.push_back({in.mesh + (flat ? 1u : 0u), in.object_to_world});
    return build_two_level(meshes, first_prim, instances, options);
}

std::vector<unsigned char> scene_node_bytes(const PreparedScene& s, NodeLayout layout) {
    if (!s.summary.instanced) return device_nodes(s.summary.accel, s.accel, layout);
    std::vector<unsigned char> bytes(s.instanced_nodes.size() * sizeof(Bvh4Node128));
    std::memcpy(bytes.data(), s.instanced_nodes.data(), bytes.size());
    return bytes;
}

std::shared_ptr<const PreparedScene> prepare_scene(const Scene& scene, const RenderSettings& settings) {
    validate_scene(scene);
    auto p = std::make_shared<PreparedScene>();
    SceneSummary& sum = p->summary;
    sum.name = scene.name;
    sum.accel = settings.accel;
    sum.features = scene_features(scene);
    sum.triangle_count = scene.placed_triangle_count();
    sum.diagonal = bounding_diagonal(scene);
    p->camera = scene.camera;

    // The environment and the light table are built for next-event estimation
    // whatever the integrator, so switching integrators rebuilds nothing.
    p->environment = load_environment_map(scene.environment);
    sum.environment_width = p->environment.width;
    sum.environment_height = p->environment.height;
    sum.environment_color = scene.environment.color;
    sum.environment_scale = scene.environment.scale;
    sum.environment_rotation = glm::radians(scene.environment.rotation_degrees);
    RenderSettings path;
    path.integrator = CLP_INTEGRATOR_PATH;
    LightTable lights =
        build_light_table(scene, kernel_features(sum.features, path), p->environment, 0.5f * sum.diagonal);
    sum.light_count = lights.lights.size();
    sum.environment_light = lights.environment;

    p->surface = pack_surface_buffers(scene);
    if (!scene.instances.empty()) {
        prepare_instanced(scene, settings, lights.light_of_triangle, *p);
    } else {
        if (settings.accel == Accel::Flat && scene.triangle_object.size() != scene.triangle_count())
            throw Error("internal: scene '" + scene.name + "' has no object id for every triangle (needed by --accel flat)");
        p->accel = build_accel(settings.accel, scene.vertices, scene.triangle_object, settings.bvh);
        for (auto& t : p->accel.triangles) t.light = lights.light_of_triangle[t.prim];
        p->triangle_material = scene.triangle_material;
        p->normals = scene.normals;
    }
    sum.bvh_stats = p->accel.stats;

    p->materials.assign(scene.materials.begin(), scene.materials.end());  // the core records
    if (sum.features.textures || sum.features.alpha || sum.features.clearcoat ||
        sum.features.transmission)  // else no kernel reads them (kernels/textures.cl)
        p->material_ext.assign(scene.materials.begin(), scene.materials.end());
    p->lights = std::move(lights.lights);
    p->light_alias = std::move(lights.alias);
    // Built where the settings pick lights by it with the path integrator
    // (the light table too is built whatever the integrator, so switching
    // integrators rebuilds nothing); 72 bytes a light, never uploaded unused.
    RenderSettings path_settings = settings;
    path_settings.integrator = CLP_INTEGRATOR_PATH;
    if (uses_light_bvh(sum.features, path_settings) && !p->lights.empty()) {
        const auto t0 = std::chrono::steady_clock::now();
        p->light_bvh = build_light_bvh(p->lights);
        LightBvhSummary& lb = sum.light_bvh;
        lb.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        lb.built = true;
        lb.origin = p->light_bvh.origin;
        lb.scale = p->light_bvh.scale;
        lb.node_count = std::uint32_t(p->light_bvh.nodes.size());
        lb.infinite_count = std::uint32_t(p->light_bvh.infinite.size());
        lb.depth = p->light_bvh.depth;
    }
    sum.attr_stride = p->surface.attr_stride;
    sum.surface_flags = p->surface.scene_flags | (p->material_ext.empty() ? 0u : CLP_SCENE_MATERIAL_EXT);
    return p;
}

}  // namespace clpath
