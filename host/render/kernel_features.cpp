#include "render/kernel_features.hpp"

#include <cmath>
#include <cstdlib>

#include "util/error.hpp"

namespace clpath {
namespace {
// Indexed by CLP_MAT_*: the kernels' switch of each kind, from the one table.
#define CLP_MAT_SWITCH(KIND, name, in_scene_files) " -DCLP_HAS_MAT_" #KIND,
const char* const kMaterialSwitches[CLP_MAT_KIND_COUNT] = {CLP_MATERIAL_KINDS(CLP_MAT_SWITCH)};
#undef CLP_MAT_SWITCH
}  // namespace

SceneFeatures scene_features(const Scene& scene) {
    SceneFeatures f;
    std::vector<bool> used(scene.materials.size(), false);
    for (auto m : scene.triangle_material) used[m] = true;
    for (const auto& mesh : scene.meshes)
        for (auto m : mesh.triangle_material) used[m] = true;
    for (std::size_t i = 0; i < used.size(); ++i) {
        if (!used[i]) continue;
        const SceneMaterial& m = scene.materials[i];
        f.materials[m.kind] = true;
        f.emission = f.emission || emits(m);
        for (int t : m.texture) f.textures = f.textures || t != CLP_NO_TEXTURE;
        f.alpha = f.alpha || m.alpha_mode != CLP_ALPHA_OPAQUE;
        if (m.kind == CLP_MAT_GLTF) {
            f.clearcoat = f.clearcoat || m.clearcoat > 0;
            f.transmission = f.transmission || m.transmission > 0;
        }
    }
    f.lights = !scene.lights.empty();
    f.environment = scene.environment.emits();
    f.environment_map = f.environment && !scene.environment.image.empty();
    f.normals = !scene.normals.empty();
    for (const auto& mesh : scene.meshes) f.normals = f.normals || !mesh.normals.empty();
    f.instances = !scene.instances.empty();
    // The finite lights (emissive triangles, point and spot lights): how
    // many, and the box around them against the scene's.
    std::size_t finite = 0;
    glm::vec3 lo(INFINITY), hi(-INFINITY), slo(INFINITY), shi(-INFINITY);
    auto grow = [](glm::vec3& a, glm::vec3& b, glm::vec3 p) {
        a = glm::min(a, p);
        b = glm::max(b, p);
    };
    for (std::size_t t = 0; t < scene.triangle_material.size(); ++t) {
        const bool lit = emits(scene.materials[scene.triangle_material[t]]);
        finite += lit ? 1 : 0;
        for (int c = 0; c < 3; ++c) {
            grow(slo, shi, scene.vertices[3 * t + std::size_t(c)]);
            if (lit) grow(lo, hi, scene.vertices[3 * t + std::size_t(c)]);
        }
    }
    for (const auto& l : scene.lights)
        if (l.type != PunctualLight::Type::Directional) {
            ++finite;
            grow(lo, hi, l.position);
            grow(slo, shi, l.position);
        }
    f.many_lights = finite >= kManyFiniteLights && glm::length(hi - lo) >= kManyLightsSpread * glm::length(shi - slo);
    f.attributes = scene.attribute_flags();
    f.vertex_colors = (f.attributes & CLP_SCENE_COLORS) != 0;
    return f;
}

bool uses_light_bvh(const SceneFeatures& scene, const RenderSettings& settings) {
    if (settings.integrator != CLP_INTEGRATOR_PATH || !(scene.emission || scene.lights || scene.environment)) return false;
    LightSampler s = settings.light_sampler;
    if (s == LightSampler::Auto) {
        if (const char* env = std::getenv("CLPATH_LIGHT_SAMPLER"); env && *env) {
            try {
                s = parse_light_sampler(env);
            } catch (const Error& e) {
                throw Error(std::string("CLPATH_LIGHT_SAMPLER: ") + e.what());
            }
        }
    }
    if (s == LightSampler::Auto) return scene.many_lights;
    return s == LightSampler::Bvh;
}

KernelFeatures kernel_features(const SceneFeatures& scene, const RenderSettings& settings) {
    KernelFeatures f;
    f.integrator = settings.integrator;
    f.max_depth = settings.max_depth;
    f.flat_accel = settings.accel == Accel::Flat;
    const bool path = settings.integrator == CLP_INTEGRATOR_PATH;
    const bool light_transport = path || settings.integrator == CLP_INTEGRATOR_PATH_BSDF;
    // A choice of estimator, not of scene: it stays a choice with every feature compiled in.
    const bool uniform = light_transport && settings.hemisphere == kHemisphereUniform;
    if (settings.all_features) {
        f.materials.fill(true);
        f.emission = f.environment = f.environment_map = f.normals = true;
        f.textures = f.vertex_colors = true;
        // Alpha changes traversal's signature (textures.cl): it follows the scene, even here.
        f.alpha = scene.alpha;
        f.alpha_attributes = scene.alpha ? scene.attributes : 0u;
        f.clearcoat = scene.clearcoat;
        f.transmission = scene.transmission;
        f.instances = scene.instances;  // the node buffer's layout: it follows the scene
        f.triangle_lights = f.delta_lights = path;
        f.uniform_hemisphere = uniform;
        f.light_bvh = uses_light_bvh(scene, settings);  // a choice of estimator, as the hemisphere
        return f;
    }
    f.materials = scene.materials;
    f.emission = scene.emission;
    f.triangle_lights = path && scene.emission;
    f.delta_lights = path && scene.lights;
    f.environment = light_transport && scene.environment;
    f.environment_map = f.environment && scene.environment_map;
    f.normals = scene.normals;
    f.textures = scene.textures;
    f.vertex_colors = scene.vertex_colors;
    f.alpha = scene.alpha;
    f.alpha_attributes = scene.alpha ? scene.attributes : 0u;
    f.instances = scene.instances;
    f.clearcoat = scene.clearcoat && scene.materials[CLP_MAT_GLTF];
    f.transmission = scene.transmission && scene.materials[CLP_MAT_GLTF];
    f.uniform_hemisphere = uniform && scene.materials[CLP_MAT_DIFFUSE];  // no diffuse surface: nothing to change
    f.light_bvh = uses_light_bvh(scene, settings);
    return f;
}

std::string build_options(const KernelFeatures& f) {
    std::string o = "-cl-std=CL1.2";
    for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k)
        if (f.materials[k]) o += kMaterialSwitches[k];
    if (f.emission) o += " -DCLP_HAS_EMISSION";
    if (f.triangle_lights) o += " -DCLP_HAS_TRIANGLE_LIGHTS";
    if (f.delta_lights) o += " -DCLP_HAS_DELTA_LIGHTS";
    if (f.environment) o += " -DCLP_HAS_ENV";
    if (f.environment_map) o += " -DCLP_HAS_ENV_MAP";
    if (f.normals) o += " -DCLP_HAS_NORMALS";
    if (f.textures) o += " -DCLP_HAS_TEXTURES";
    if (f.vertex_colors) o += " -DCLP_HAS_VERTEX_COLORS";
    if (f.alpha) o += " -DCLP_HAS_ALPHA -DCLP_ALPHA_ATTRIBUTES=" + std::to_string(f.alpha_attributes) + "u";
    if (f.clearcoat) o += " -DCLP_HAS_CLEARCOAT";
    if (f.transmission) o += " -DCLP_HAS_TRANSMISSION";
    if (f.flat_accel) o += " -DCLP_ACCEL_FLAT";
    if (f.instances) o += " -DCLP_HAS_INSTANCES";
    if (f.light_bvh) o += " -DCLP_LIGHT_BVH";
    if (f.uniform_hemisphere) o += " -DCLP_UNIFORM_HEMISPHERE";
    o += " -DCLP_INTEGRATOR=" + std::to_string(f.integrator) + "u";
    o += " -DCLP_MAX_DEPTH=" + std::to_string(f.max_depth) + "u";
    return o;
}

}  // namespace clpath
