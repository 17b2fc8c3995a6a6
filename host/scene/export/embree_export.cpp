#include "scene/export/embree_export.hpp"

#include <cstdio>
#include <vector>

#include "scene/export/obj_export.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::string num(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}
std::string vec(glm::vec3 v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }

}  // namespace

EmbreeExport export_embree_scene(const Scene& scene, const std::string& stem, const std::string& source) {
    std::vector<bool> used(scene.materials.size(), false);
    for (auto m : scene.triangle_material) used.at(m) = true;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const std::string name = i < scene.material_names.size() ? scene.material_names[i] : std::to_string(i);
        if (scene.materials[i].kind != CLP_MAT_DIFFUSE)
            throw Error("material '" + name + "' is a " + material_kind_name(scene.materials[i].kind) +
                        ": only diffuse surfaces are exported for Embree's pathtracer");
        if (emits(scene.materials[i]))
            throw Error("material '" + name + "' emits light: Embree's pathtracer ignores MTL's Ke, so only point "
                        "lights are exported for it");
    }
    if (!scene.normals.empty())
        throw Error("the scene has shading normals: only flat-shaded scenes are exported for Embree's pathtracer");
    for (const auto& l : scene.lights)
        if (l.type != PunctualLight::Type::Point)
            throw Error(std::string("the scene has a ") +
                        (l.type == PunctualLight::Type::Spot ? "spot" : "directional") +
                        " light: only point lights are exported for Embree's pathtracer");
    if (scene.lights.empty()) throw Error("the scene has no point light: Embree's pathtracer would render it black");
    if (scene.environment.emits())
        throw Error("the scene has an environment: Embree's pathtracer would not see it as clpath does");
    if (!scene.colors.empty()) throw Error("the mesh has vertex colours, which MTL cannot hold");
    if (scene.triangle_count() == 0) throw Error("the scene has no triangles");

    const ObjMeshText mesh = obj_mesh_text(scene, stem, source);
    EmbreeExport out;
    out.obj = mesh.obj;
    out.mtl = mesh.mtl;
    const Camera& c = scene.camera;
    out.ecs = "# clpath export of '" + scene.name + "' from " + source +
              " for Embree's example path tracer: pathtracer -c " + stem + ".ecs\n"
              "# camera (vertical field of view in degrees), image size, point lights (position, intensity in W/sr)\n"
              "-i " + stem + ".obj\n"
              "--vp " + vec(c.eye) + "\n--vi " + vec(c.target) + "\n--vu " + vec(c.up) + "\n--fov " +
              num(c.vfov_degrees) + "\n--size " + std::to_string(c.width) + " " + std::to_string(c.height) + "\n";
    for (const auto& l : scene.lights) out.ecs += "--pointlight " + vec(l.position) + " " + vec(l.intensity) + "\n";
    out.ecs += "# samples per pixel; path length = clpath's max depth (the same point-light estimator)\n"
               "--spp " + std::to_string(scene.render.spp) + "\n--max-path-length " +
               std::to_string(scene.render.max_depth) + "\n";
    return out;
}

}  // namespace clpath
