#include "scene/scene.hpp"

#include <cmath>

#include "util/error.hpp"

namespace clpath {

const char* material_kind_name(std::uint32_t kind) {
#define CLP_MAT_NAME(KIND, name, in_scene_files) #name,
    static const char* const names[] = {CLP_MATERIAL_KINDS(CLP_MAT_NAME)};
#undef CLP_MAT_NAME
    if (kind >= CLP_MAT_KIND_COUNT) throw Error("internal: material kind " + std::to_string(kind) + " is not in the table");
    return names[kind];
}

bool material_kind_in_scene_files(std::uint32_t kind) {
#define CLP_MAT_IN_FILES(KIND, name, in_scene_files) bool(in_scene_files),
    static const bool in_files[] = {CLP_MATERIAL_KINDS(CLP_MAT_IN_FILES)};
#undef CLP_MAT_IN_FILES
    return kind < CLP_MAT_KIND_COUNT && in_files[kind];
}

float Camera::resolved_focus_distance() const {
    return focus_distance > 0.0f ? focus_distance : glm::length(target - eye);
}

CameraData camera_data(const Camera& c) {
    const glm::vec3 view = c.target - c.eye;
    if (!(glm::length(view) > 0.0f) || !std::isfinite(glm::length(view)))
        throw Error("camera: eye and target must be distinct finite points");
    if (!(c.ortho_half_height >= 0.0f) || !std::isfinite(c.ortho_half_height))
        throw Error("camera: an orthographic camera's half-height must be a finite number above 0");
    if (c.ortho_half_height == 0 && !(c.vfov_degrees > 0.0f && c.vfov_degrees < 180.0f))
        throw Error("camera: vertical field of view must be in (0, 180) degrees, got " +
                    std::to_string(c.vfov_degrees));
    if (c.width <= 0 || c.height <= 0) throw Error("camera: width and height must be positive");
    if (!(c.aperture_radius >= 0.0f) || !std::isfinite(c.aperture_radius))
        throw Error("camera: the aperture radius must be a finite number >= 0, got " + std::to_string(c.aperture_radius));
    if (!(c.focus_distance >= 0.0f) || !std::isfinite(c.focus_distance))
        throw Error("camera: the focus distance must be a finite number > 0 (or 0: the target's distance), got " +
                    std::to_string(c.focus_distance));
    if (c.ortho_half_height > 0 && c.has_lens())
        throw Error("camera: an orthographic camera has no lens (aperture radius must be 0)");
    const glm::vec3 forward = glm::normalize(view);
    const glm::vec3 side = glm::cross(forward, c.up);
    if (!(glm::length(side) > 1e-6f * glm::length(c.up)))
        throw Error("camera: up must not be parallel to the view direction");
    const glm::vec3 right = glm::normalize(side);
    const glm::vec3 up = glm::cross(right, forward);
    const float ty = c.ortho_half_height > 0 ? c.ortho_half_height : std::tan(glm::radians(c.vfov_degrees) * 0.5f);
    const float tx = ty * float(c.width) / float(c.height);
    CameraData d{};
    store3(d.eye, c.eye);
    store3(d.forward, forward);
    store3(d.right, right * tx);
    store3(d.up, up * ty);
    d.orthographic = c.ortho_half_height > 0 ? 1u : 0u;
    d.width = std::uint32_t(c.width);
    d.height = std::uint32_t(c.height);
    if (c.has_lens()) {
        d.lens_radius = c.aperture_radius;
        d.focus_distance = c.resolved_focus_distance();
    }
    return d;
}

std::uint32_t Scene::add_material(const std::string& name, const SceneMaterial& m) {
    for (const auto& n : material_names)
        if (n == name) throw Error("material '" + name + "' defined twice");
    materials.push_back(m);
    material_names.push_back(name);
    return std::uint32_t(materials.size() - 1);
}

void Scene::add_triangles(const std::vector<glm::vec3>& tris, std::uint32_t material) {
    vertices.insert(vertices.end(), tris.begin(), tris.end());
    triangle_object.insert(triangle_object.end(), tris.size() / 3, next_object_id());
    triangle_material.insert(triangle_material.end(), tris.size() / 3, material);
    if (!uvs.empty()) uvs.resize(vertices.size(), glm::vec2(0));
    if (!tangents.empty()) tangents.resize(vertices.size(), glm::vec4(0));
    if (!colors.empty()) colors.resize(vertices.size(), glm::vec4(1));
}

std::size_t Scene::placed_triangle_count() const {
    std::size_t n = triangle_count();
    for (const auto& i : instances) n += i.mesh < meshes.size() ? meshes[i.mesh].triangle_count() : 0;
    return n;
}

Scene flatten_instances(const Scene& scene, std::size_t max_triangles) {
    Scene s = scene;
    s.meshes.clear();
    s.instances.clear();
    if (scene.placed_triangle_count() > max_triangles)
        throw Error("scene '" + scene.name + "': flattening its instances gives " +
                    std::to_string(scene.placed_triangle_count()) + " triangles, more than " +
                    std::to_string(max_triangles));
    bool normals = !s.normals.empty();
    for (const auto& in : scene.instances) normals = normals || !scene.meshes[in.mesh].normals.empty();
    if (normals) s.normals.resize(s.vertices.size(), glm::vec3(0));  // zero: none, shaded flat
    // Attributes as SceneBuilder gives a transformed mesh's, with its defaults
    // (no uv, a tangent to derive, white) where a mesh has none.
    const std::uint32_t attributes = scene.attribute_flags();
    if (attributes & CLP_SCENE_UVS) s.uvs.resize(s.vertices.size(), glm::vec2(0));
    if (attributes & CLP_SCENE_TANGENTS) s.tangents.resize(s.vertices.size(), glm::vec4(0));
    if (attributes & CLP_SCENE_COLORS) s.colors.resize(s.vertices.size(), glm::vec4(1));
    for (const auto& in : scene.instances) {
        const InstancedMesh& m = scene.meshes[in.mesh];
        const glm::mat3 l(in.object_to_world);
        const bool flip = glm::determinant(l) < 0;
        const glm::mat3 normal_m = glm::transpose(glm::inverse(l));
        const std::uint32_t object = s.next_object_id();
        for (std::size_t t = 0; t < m.triangle_count(); ++t) {
            const std::size_t corner[3] = {3 * t, 3 * t + (flip ? 2 : 1), 3 * t + (flip ? 1 : 2)};
            for (std::size_t c : corner) {
                s.vertices.push_back(glm::vec3(in.object_to_world * glm::vec4(m.vertices[c], 1.0f)));
                if (attributes & CLP_SCENE_UVS) s.uvs.push_back(m.uvs.empty() ? glm::vec2(0) : m.uvs[c]);
                if (attributes & CLP_SCENE_COLORS) s.colors.push_back(m.colors.empty() ? glm::vec4(1) : m.colors[c]);
                if (attributes & CLP_SCENE_TANGENTS)
                    s.tangents.push_back(m.tangents.empty() ? glm::vec4(0) : moved_tangent(l, flip, m.tangents[c]));
                if (!normals) continue;
                const glm::vec3 n = m.normals.empty() ? glm::vec3(0) : normal_m * m.normals[c];
                const float len = glm::length(n);
                s.normals.push_back(len > 0 && std::isfinite(len) ? n / len : glm::vec3(0));
            }
            s.triangle_material.push_back(m.triangle_material[t]);
            s.triangle_object.push_back(object);
        }
    }
    return s;
}

glm::vec4 moved_tangent(const glm::mat3& linear, bool mirrors, glm::vec4 tangent) {
    const glm::vec3 d = linear * glm::vec3(tangent);
    const float len = glm::length(d);
    if (!(len > 0) || !std::isfinite(len)) return glm::vec4(0);
    return glm::vec4(d / len, (tangent.w < 0 ? -1.0f : 1.0f) * (mirrors ? -1.0f : 1.0f));
}

std::uint32_t Scene::attribute_flags() const {
    bool uv = !uvs.empty(), tangent = !tangents.empty(), color = !colors.empty();
    for (const auto& m : meshes) {
        uv = uv || !m.uvs.empty();
        tangent = tangent || !m.tangents.empty();
        color = color || !m.colors.empty();
    }
    return (uv ? CLP_SCENE_UVS : 0u) | (tangent ? CLP_SCENE_TANGENTS : 0u) | (color ? CLP_SCENE_COLORS : 0u);
}

bool Scene::has_emitter() const {
    if (!lights.empty() || environment.emits()) return true;
    std::vector<bool> used(materials.size(), false);
    for (auto m : triangle_material)
        if (m < used.size()) used[m] = true;
    for (std::size_t i = 0; i < materials.size(); ++i)
        if (used[i] && emits(materials[i])) return true;
    return false;
}

SceneMaterial base_material() {
    SceneMaterial m{};
    for (int& t : m.texture) t = CLP_NO_TEXTURE;
    m.alpha = 1;
    m.alpha_cutoff = 0.5f;
    m.normal_scale = 1;
    m.clearcoat_normal_scale = 1;
    m.ior = 1.5f;
    return m;
}

SceneMaterial gltf_material(glm::vec3 base_color, float metallic, float roughness) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_GLTF;
    store3(m.albedo, base_color);
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

SceneMaterial diffuse(glm::vec3 albedo) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_DIFFUSE;
    store3(m.albedo, albedo);
    return m;
}

SceneMaterial mirror(glm::vec3 tint) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_MIRROR;
    store3(m.albedo, tint);
    return m;
}

SceneMaterial conductor(glm::vec3 f0, float roughness) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_CONDUCTOR;
    store3(m.albedo, f0);
    m.roughness = roughness;
    return m;
}

SceneMaterial dielectric(float ior, float roughness, glm::vec3 tint) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_DIELECTRIC;
    store3(m.albedo, tint);
    m.ior = ior;
    m.roughness = roughness;
    return m;
}

SceneMaterial emitter(glm::vec3 radiance, bool two_sided, glm::vec3 albedo) {
    SceneMaterial m = base_material();
    m.kind = CLP_MAT_DIFFUSE;
    store3(m.emission, radiance);
    store3(m.albedo, albedo);
    m.flags = two_sided ? CLP_MATF_TWO_SIDED_EMISSION : 0u;
    return m;
}

}  // namespace clpath
