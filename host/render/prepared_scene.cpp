#include "render/prepared_scene.hpp"

#include <cmath>

#include "util/error.hpp"

namespace clpath {
namespace {

void validate_scene(const Scene& s) {
    if (s.triangle_count() == 0) throw Error("scene '" + s.name + "' has no triangles");
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

float bounding_diagonal(const std::vector<glm::vec3>& vertices) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const float d = glm::length(hi - lo);
    return d > 0 && std::isfinite(d) ? d : 1.0f;
}

}  // namespace

std::shared_ptr<const PreparedScene> prepare_scene(const Scene& scene, const RenderSettings& settings) {
    validate_scene(scene);
    auto p = std::make_shared<PreparedScene>();
    SceneSummary& sum = p->summary;
    sum.name = scene.name;
    sum.accel = settings.accel;
    sum.features = scene_features(scene);
    sum.triangle_count = scene.triangle_count();
    sum.diagonal = bounding_diagonal(scene.vertices);
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

    if (settings.accel == Accel::Flat && scene.triangle_object.size() != scene.triangle_count())
        throw Error("internal: scene '" + scene.name + "' has no object id for every triangle (needed by --accel flat)");
    p->accel = build_accel(settings.accel, scene.vertices, scene.triangle_object, settings.bvh);
    sum.bvh_stats = p->accel.stats;
    for (auto& t : p->accel.triangles) t.light = lights.light_of_triangle[t.prim];

    p->triangle_material = scene.triangle_material;
    p->materials.assign(scene.materials.begin(), scene.materials.end());  // the core records
    if (sum.features.textures || sum.features.alpha || sum.features.clearcoat ||
        sum.features.transmission)  // else no kernel reads them (kernels/textures.cl)
        p->material_ext.assign(scene.materials.begin(), scene.materials.end());
    p->normals = scene.normals;
    p->lights = std::move(lights.lights);
    p->light_alias = std::move(lights.alias);
    p->surface = pack_surface_buffers(scene);
    sum.attr_stride = p->surface.attr_stride;
    sum.surface_flags = p->surface.scene_flags | (p->material_ext.empty() ? 0u : CLP_SCENE_MATERIAL_EXT);
    return p;
}

}  // namespace clpath
