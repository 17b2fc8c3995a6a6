#include "scene/load/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/load/gltf_scene.hpp"
#include "scene/json_fields.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/load/obj_textures.hpp"
#include "scene/load/scene_instances.hpp"
#include "scene/render_names.hpp"
#include "scene/scene_builder.hpp"
#include "scene/shapes.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// "normalize": the mesh's bounding box [lo, hi] centred on the origin with
// its longest side 1; the identity for an empty or non-finite box.
glm::mat4 fit_to_unit_box(glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 ext = hi - lo;
    const float longest = std::max({ext.x, ext.y, ext.z});
    if (!(longest > 0) || !std::isfinite(longest)) return glm::mat4(1);
    return glm::scale(glm::mat4(1), glm::vec3(1 / longest)) * glm::translate(glm::mat4(1), -(lo + hi) * 0.5f);
}

namespace fs = std::filesystem;
using jsonf::Object;
using jsonf::Range;
using jsonf::Value;
using jsonf::Where;

constexpr int kMaxResolution = 16384;
const Range kFov{0, 180, true, true};
const Range kIor{0, 100, true, false};
const Range kSpotAngle{0, 90, true, false};

// Relative paths in a scene are relative to the scene file's folder.
std::string resolve(const std::string& scene_file, const std::string& path) {
    const fs::path p(path);
    if (p.is_absolute()) return path;
    return (fs::path(scene_file).parent_path() / p).lexically_normal().string();
}

std::string stem(const std::string& file) { return fs::path(file).stem().string(); }

void read_camera(Object o, Camera& cam) {
    cam.eye = o.require("eye").vec3();
    cam.target = o.require("target").vec3();
    if (auto v = o.get("up")) cam.up = v->vec3();
    if (auto v = o.get("vfov")) cam.vfov_degrees = v->real(kFov);
    if (auto v = o.get("aperture_radius")) cam.aperture_radius = v->real(jsonf::kNonNegative);
    if (auto v = o.get("focus_distance")) cam.focus_distance = v->real(jsonf::kPositive);
    if (auto v = o.get("resolution")) {
        const auto a = v->array();
        if (a.size() != 2) v->fail("expected [width, height]");
        cam.width = int(a[0].integer(1, kMaxResolution));
        cam.height = int(a[1].integer(1, kMaxResolution));
    }
    o.finish();
    try {
        (void)camera_data(cam);
    } catch (const Error& e) {
        std::string what = e.what();
        if (what.rfind("camera: ", 0) == 0) what = what.substr(8);
        o.where().fail(what);
    }
}

void read_render(Object o, SceneRenderDefaults& r) {
    if (auto v = o.get("spp")) r.spp = std::uint32_t(v->integer(1, 0xffffffffll));
    if (auto v = o.get("max_depth")) r.max_depth = std::uint32_t(v->integer(0, 1024));
    if (auto v = o.get("seed")) r.seed = std::uint32_t(v->integer(0, 0xffffffffll));
    if (auto v = o.get("ao_distance")) r.ao_distance = v->real(jsonf::kNonNegative);
    if (auto v = o.get("noise_target")) {
        r.noise_target = v->real(jsonf::kPositive);
        if (r.noise_target > 1) v->fail("a noise target is at most 1");
    }
    // The names are the command line's; scene/render_names.cpp owns the lists.
    auto name = [](const Value& v, auto parse) {
        const std::string s = v.string();
        try {
            parse(s);
        } catch (const Error& e) {
            v.fail(e.what());
        }
        return s;
    };
    if (auto v = o.get("russian_roulette")) r.russian_roulette = name(*v, parse_rr_rule);
    if (auto v = o.get("integrator")) r.integrator = name(*v, parse_integrator);
    if (auto v = o.get("light_sampler"))
        r.light_sampler = name(*v, [](const std::string& s) {
            const auto& names = light_sampler_names();
            if (std::find(names.begin(), names.end(), s) == names.end())
                throw Error("unknown light sampler '" + s + "' (choose one of: auto, power, bvh)");
        });
    o.finish();
}

SceneMaterial read_material(Object o) {
    const Value type_v = o.require("type");
    std::string type = type_v.string();
    // Aliases the thesis text uses.
    if (type == "glossy") type = "conductor";
    if (type == "glass") type = "dielectric";
    const auto color = o.get_one_of({"albedo", "color", "tint", "f0"});
    const auto emission = o.get_one_of({"emission", "radiance"});
    const auto strength = o.get("strength");
    const auto two_sided = o.get("two_sided");
    std::optional<Value> roughness, ior;
    if (type == "conductor" || type == "dielectric") roughness = o.get("roughness");
    if (type == "dielectric") ior = o.get("ior");

    SceneMaterial m;
    const glm::vec3 c = color ? color->color(jsonf::kUnit) : glm::vec3(type == "diffuse" ? 0.8f : type == "emitter" ? 0.0f : 1.0f);
    const float rough = roughness ? roughness->real(jsonf::kUnit) : 0.0f;
    if (type == "diffuse") {
        m = diffuse(c);
    } else if (type == "emitter") {
        if (!emission) o.where().key("emission").fail("required for an emitter");
        m = emitter(glm::vec3(0), false, c);
    } else if (type == "mirror") {
        m = mirror(c);
    } else if (type == "conductor") {
        m = conductor(c, rough);
    } else if (type == "dielectric") {
        m = dielectric(ior ? ior->real(kIor) : 1.5f, rough, c);
    } else {
        std::string choices;
        for (std::uint32_t k = 0; k < CLP_MAT_KIND_COUNT; ++k)
            if (material_kind_in_scene_files(k)) choices += std::string(material_kind_name(k)) + ", ";
        type_v.fail("unknown material type '" + type + "' (choose one of: " + choices +
                    "or the aliases emitter (diffuse of albedo 0 that emits), glossy (conductor), glass (dielectric))");
    }
    glm::vec3 e = emission ? emission->color(jsonf::kNonNegative) : glm::vec3(0);
    if (strength) e *= strength->real(jsonf::kNonNegative);
    if (!std::isfinite(e.x + e.y + e.z)) (strength ? *strength : *emission).fail("emission times strength is not finite");
    for (int i = 0; i < 3; ++i) m.emission[i] = e[i];
    if (two_sided && two_sided->boolean()) m.flags |= CLP_MATF_TWO_SIDED_EMISSION;
    o.finish();
    return m;
}

glm::mat4 read_transform(std::optional<Value> v) {
    if (!v) return glm::mat4(1);
    Object o(*v);
    glm::vec3 t(0), r(0), s(1);
    if (auto x = o.get("translate")) t = x->vec3();
    if (auto x = o.get("rotate")) r = x->vec3(Range{-36000, 36000});
    if (auto x = o.get("scale")) s = x->scalar_or_vec3(jsonf::kAny);
    o.finish();
    return shape_transform(t, glm::radians(r), s);
}

Bumps read_bumps(const Value& v, bool with_function) {
    Object o(v);
    Bumps b;
    b.kind = Bumps::Kind::Sine;
    if (with_function) {
        const Value f = o.require("function");
        const std::string name = f.string();
        if (name == "sine") b.kind = Bumps::Kind::Sine;
        else if (name == "ripple") b.kind = Bumps::Kind::Ripple;
        else if (name == "flat") b.kind = Bumps::Kind::None;
        else f.fail("unknown height function '" + name + "' (choose one of: sine, ripple, flat)");
    }
    b.amplitude = o.require("amplitude").real(Range{-10, 10});
    if (auto f = o.get("frequency")) b.frequency = f->real(Range{0, 10000});
    o.finish();
    return b;
}

bool textured(const ObjMaterial& om) { return !om.diffuse_texture.empty() || !om.alpha_texture.empty(); }

std::vector<bool> used_materials(const ObjMesh& mesh) {
    std::vector<bool> used(mesh.materials.size(), false);
    for (int mi : mesh.triangle_material)
        if (mi >= 0) used[std::size_t(mi)] = true;
    return used;
}

std::size_t icosphere_triangles(int level) { return std::size_t(20) << (2 * level); }

class SceneReader {
public:
    SceneReader(const std::string& file, const LoadOptions& options)
        : file_(file), options_(options), builder_(scene_, options.max_triangles) {}

    Scene read(const std::string& text) {
        const jsonf::json doc = jsonf::parse(text, file_);
        Object root(Value(doc, Where{file_, ""}));
        // Every top-level field is asked for first, so that a misspelt one is
        // reported before any mesh is read.
        const auto name = root.get("name");
        const auto description = root.get("description");
        const auto camera = root.get("camera");
        const auto render = root.get("render");
        const auto materials = root.get("materials");
        const auto objects = root.get("objects");
        const auto lights = root.get("lights");
        const auto environment = root.get("environment");
        root.finish();

        scene_.name = name ? name->string() : stem(file_);
        if (description) (void)description->string();
        if (!camera) root.where().key("camera").fail("required field is missing");
        read_camera(Object(*camera), scene_.camera);
        if (render) read_render(Object(*render), scene_.render);
        if (materials) {
            Object mo(*materials);
            for (auto& [key, v] : mo.entries()) {
                if (key.empty()) v.fail("a material needs a non-empty name");
                material_index_[key] = scene_.add_material(key, read_material(Object(v)));
            }
        }
        if (!objects) root.where().key("objects").fail("required field is missing (a scene needs at least one object)");
        const auto list = objects->array();
        if (list.empty()) objects->fail("the scene is empty: it needs at least one object");
        for (const auto& o : list) read_object(Object(o));
        if (lights)
            for (const auto& l : lights->array()) scene_.lights.push_back(read_light(Object(l)));
        if (environment) read_environment(Object(*environment));

        builder_.finish();
        if (scene_.triangle_count() == 0 && scene_.instances.empty())
            objects->fail("the scene has no triangles left: all " + std::to_string(builder_.dropped()) +
                          " were degenerate");
        return std::move(scene_);
    }

private:
    std::uint32_t scene_material(const Value& v) {
        const std::string name = v.string();
        auto it = material_index_.find(name);
        if (it == material_index_.end()) {
            std::string names;
            for (const auto& n : scene_.material_names) names += (names.empty() ? "" : ", ") + n;
            v.fail("no material named '" + name + "'" + (names.empty() ? " (the scene defines none)" : " (defined: " + names + ")"));
        }
        return it->second;
    }

    // A material for the mesh's own, added once per name however often the mesh is used.
    std::uint32_t mesh_material(const std::string& name, const SceneMaterial& m) {
        auto it = material_index_.find(name);
        if (it != material_index_.end()) return it->second;
        return material_index_[name] = scene_.add_material(name, m);
    }

    void read_object(Object o) {
        const Value type_v = o.require("type");
        const std::string type = type_v.string();
        static const std::vector<std::string> kTypes{"plane", "box", "icosphere", "sphere", "grid", "mesh"};
        if (std::find(kTypes.begin(), kTypes.end(), type) == kTypes.end())
            type_v.fail("unknown object type '" + type + "' (choose one of: plane, box, icosphere, sphere, grid, mesh)");
        const std::string label = o.where().str();
        const auto name = o.get("name");
        if (name) (void)name->string();
        const glm::mat4 m = read_transform(o.get("transform"));
        if (type == "mesh") return read_mesh(o, m);

        const std::uint32_t mat = scene_material(o.require("material"));
        ShapeMesh shape;
        if (type == "plane") {
            glm::vec2 size(1);
            if (auto v = o.get("size")) {
                const auto a = v->array();
                if (a.size() != 2) v->fail("expected [x, z]");
                size = {a[0].real(jsonf::kPositive), a[1].real(jsonf::kPositive)};
            }
            shape.vertices = transformed(make_plane(), glm::scale(glm::mat4(1), glm::vec3(size.x, 1, size.y)));
        } else if (type == "box") {
            const glm::vec3 size = o.get("size") ? o.get("size")->scalar_or_vec3(jsonf::kPositive) : glm::vec3(1);
            shape.vertices = transformed(make_box(), glm::scale(glm::mat4(1), size));
        } else if (type == "icosphere" || type == "sphere") {
            const float radius = o.get("radius") ? o.get("radius")->real(jsonf::kPositive) : 1.0f;
            const bool smooth = o.get("smooth") ? o.get("smooth")->boolean() : false;
            if (type == "icosphere") {
                const int level = o.get("subdivisions") ? int(o.get("subdivisions")->integer(0, 10)) : 2;
                builder_.reserve(icosphere_triangles(level), label);
                shape = make_smooth_icosphere(level);
            } else {
                const auto tri = o.get("triangles");
                const std::size_t n = tri ? std::size_t(tri->integer(12, std::int64_t(options_.max_triangles))) : 1280;
                const auto [rings, segments] = uv_sphere_resolution(n);
                builder_.reserve(std::size_t(2) * segments * (rings - 1), label);
                Bumps bumps;
                if (auto d = o.get("displacement")) bumps = read_bumps(*d, false);
                shape = make_uv_sphere(n, bumps);
            }
            if (!smooth) shape.normals.clear();
            for (auto& v : shape.vertices) v *= radius;
        } else if (type == "grid") {
            glm::vec2 size(1);
            if (auto v = o.get("size")) {
                const auto a = v->array();
                if (a.size() != 2) v->fail("expected [x, z]");
                size = {a[0].real(jsonf::kPositive), a[1].real(jsonf::kPositive)};
            }
            int nx = 16, nz = 16;
            const auto res = o.get("resolution");
            const auto tri = o.get("triangles");
            if (res && tri) tri->fail("give either resolution or triangles, not both");
            if (res) {
                const auto a = res->array();
                if (a.size() != 2) res->fail("expected [cells along x, cells along z]");
                nx = int(a[0].integer(1, 1 << 20));
                nz = int(a[1].integer(1, 1 << 20));
            } else if (tri) {
                const auto n = tri->integer(2, std::int64_t(options_.max_triangles));
                nx = nz = std::max(1, int(std::lround(std::sqrt(double(n) / 2.0))));
            }
            builder_.reserve(std::size_t(2) * std::size_t(nx) * std::size_t(nz), label);
            Bumps height;
            if (auto h = o.get("height")) height = read_bumps(*h, true);
            const bool smooth = o.get("smooth") ? o.get("smooth")->boolean() : false;
            shape = make_grid(nx, nz, height);
            if (!smooth) shape.normals.clear();
            const glm::mat4 s = glm::scale(glm::mat4(1), glm::vec3(size.x, 1, size.y));
            for (auto& v : shape.vertices) v = glm::vec3(s * glm::vec4(v, 1));
            for (auto& n : shape.normals) n = glm::normalize(glm::vec3(n.x / size.x, n.y, n.z / size.y));
        }
        o.finish();
        builder_.add(shape.vertices, shape.normals, m, {mat}, label);
    }

    void read_mesh(Object& o, const glm::mat4& m) {
        const std::string label = o.where().str();
        const Value file_v = o.require("file");
        const std::string path = resolve(file_, file_v.string());
        const auto material = o.get("material");
        const auto materials = o.get("materials");
        const bool smooth = o.get("smooth") ? o.get("smooth")->boolean() : true;
        const bool normalize = o.get("normalize") ? o.get("normalize")->boolean() : false;
        const auto instances = o.get("instances");
        o.finish();
        const std::vector<glm::mat4> placements =
            instances ? read_instance_transforms(*instances) : std::vector<glm::mat4>{};
        if (instances && is_gltf_file(path))
            instances->fail("instances of a glTF model are not supported: its nodes place its meshes (and share them)");
        if (is_gltf_file(path)) return read_gltf(file_v, path, material, materials, smooth, normalize, m, label);

        auto& cached = meshes_[path];
        if (!cached) {
            // A file that cannot be read is the scene's fault, named by its field;
            // a fault inside the mesh names the mesh's own file and line.
            std::string text;
            try {
                text = options_.read_file(path);
            } catch (const Error& e) {
                file_v.fail(e.what());
            }
            cached = std::make_shared<ObjMesh>(parse_obj(text, path, options_.read_file));
            scene_.warnings.insert(scene_.warnings.end(), cached->warnings.begin(), cached->warnings.end());
        }
        const ObjMesh& mesh = *cached;

        // Materials: an override by name, else the scene-wide "material", else the MTL's own.
        std::map<std::string, std::uint32_t> overrides;
        if (materials) {
            Object mo(*materials);
            for (auto& [key, v] : mo.entries()) {
                bool used = false;
                for (const auto& om : mesh.materials) used = used || om.name == key;
                if (!used) v.fail("the mesh " + path + " uses no material named '" + key + "'");
                overrides[key] = scene_material(v);
            }
        }
        const bool has_all = material.has_value();
        const std::uint32_t all = has_all ? scene_material(*material) : 0;
        std::vector<std::uint32_t> index(mesh.materials.size());
        const std::vector<bool> used = used_materials(mesh);
        for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
            const ObjMaterial& om = mesh.materials[i];
            if (!used[i] && textured(om)) continue;  // its images are not loaded for nothing
            if (auto it = overrides.find(om.name); it != overrides.end()) index[i] = it->second;
            else if (has_all) index[i] = all;
            else if (om.defined) {
                const std::string name = path + ":" + om.name;
                auto it = material_index_.find(name);
                index[i] = it != material_index_.end() ? it->second
                                                       : mesh_material(name, obj_material_with_textures(scene_, om, options_));
            } else {
                // As other tools load such a file: grey, with a warning.
                scene_.warnings.push_back(path + ":" + std::to_string(om.usemtl_line) + ": usemtl '" + om.name +
                                          "': no .mtl file defines it, and " + label +
                                          " gives no material for it (\"material\" or \"materials\"); it is the "
                                          "default grey");
                index[i] = mesh_material(path + ":(default)", diffuse(glm::vec3(0.8f)));
            }
        }
        std::vector<std::uint32_t> tri_mat(mesh.triangle_count());
        bool needs_default = false;
        for (std::size_t t = 0; t < tri_mat.size(); ++t) {
            const int mi = mesh.triangle_material[t];
            if (mi >= 0) tri_mat[t] = index[std::size_t(mi)];
            else needs_default = true;
        }
        if (needs_default) {
            const std::uint32_t d = has_all ? all : mesh_material(path + ":(default)", diffuse(glm::vec3(0.8f)));
            for (std::size_t t = 0; t < tri_mat.size(); ++t)
                if (mesh.triangle_material[t] < 0) tri_mat[t] = d;
        }
        glm::mat4 place = m;
        if (normalize && !mesh.vertices.empty()) {
            glm::vec3 lo(INFINITY), hi(-INFINITY);
            for (const auto& v : mesh.vertices) {
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
            place = m * fit_to_unit_box(lo, hi);
        }
        if (mesh.triangle_count() == 0) {
            scene_.warnings.push_back(label + ": the mesh " + path + " has no faces");
            return;
        }
        static const std::vector<glm::vec3> kNone;
        VertexAttributes attr{&mesh.uvs, nullptr, &mesh.colors};
        if (instances)
            return place_mesh_instances(scene_, builder_, label, mesh.vertices, smooth ? mesh.normals : kNone, tri_mat,
                                        place, placements, attr);
        builder_.add(mesh.vertices, smooth ? mesh.normals : kNone, place, tri_mat, label, attr);
    }

    // A glTF model as a mesh: its materials unless the object overrides them
    // ("material" for all, "materials" by glTF material name), its lights; its cameras are not used.
    void read_gltf(const Value& file_v, const std::string& path, const std::optional<Value>& material,
                   const std::optional<Value>& materials, bool smooth, bool normalize, glm::mat4 place,
                   const std::string& label) {
        const bool exists = options_.file_exists ? options_.file_exists(path) : fs::is_regular_file(path);
        if (!exists) file_v.fail(path + ": no such file");
        const GltfModel model = load_gltf(path, options_);
        scene_.warnings.insert(scene_.warnings.end(), model.warnings.begin(), model.warnings.end());
        std::map<int, std::uint32_t> by_index;
        if (materials) {
            Object mo(*materials);
            for (auto& [key, v] : mo.entries()) {
                int found = -2;
                for (std::size_t i = 0; i < model.materials.size(); ++i)
                    if (model.materials[i].name == key) found = int(i);
                if (found == -2) v.fail("the model " + path + " has no material named '" + key + "'");
                by_index[found] = scene_material(v);
            }
        }
        const std::optional<std::uint32_t> all = material ? std::optional(scene_material(*material)) : std::nullopt;
        auto override_for = [&](int gm) {
            if (auto it = by_index.find(gm); it != by_index.end()) return it->second;
            return all ? *all : std::numeric_limits<std::uint32_t>::max();
        };
        if (model.triangle_count() == 0) {
            scene_.warnings.push_back(label + ": the model " + path + " places no triangles");
            return;
        }
        if (normalize) {
            glm::vec3 lo(INFINITY), hi(-INFINITY);
            for (const auto& inst : model.instances)
                for (const auto& p : model.meshes[inst.mesh])
                    for (const auto& v : p.vertices) {
                        const glm::vec3 w(inst.world * glm::vec4(v, 1));
                        lo = glm::min(lo, w);
                        hi = glm::max(hi, w);
                    }
            place = place * fit_to_unit_box(lo, hi);
        }
        add_gltf(scene_, builder_, model, place, path, smooth, override_for);
    }

    PunctualLight read_light(Object o) {
        PunctualLight l;
        const Value type_v = o.require("type");
        const std::string type = type_v.string();
        auto direction = [&](const Value& v) {
            const glm::vec3 d = v.vec3();
            if (!(glm::length(d) > 0)) v.fail("a direction must not be zero");
            return glm::normalize(d);
        };
        if (type == "point" || type == "spot") {
            l.type = type == "point" ? PunctualLight::Type::Point : PunctualLight::Type::Spot;
            l.position = o.require("position").vec3();
        } else if (type == "directional") {
            l.type = PunctualLight::Type::Directional;
        } else {
            type_v.fail("unknown light type '" + type + "' (choose one of: point, spot, directional)");
        }
        l.intensity = o.require("intensity").color(jsonf::kNonNegative);
        if (l.type == PunctualLight::Type::Directional) l.direction = direction(o.require("direction"));
        if (l.type == PunctualLight::Type::Spot) {
            const auto dir = o.get("direction");
            const auto target = o.get("target");
            if (dir && target) target->fail("give either direction or target, not both");
            if (dir) l.direction = direction(*dir);
            else if (target) {
                const glm::vec3 d = target->vec3() - l.position;
                if (!(glm::length(d) > 0)) target->fail("the target must differ from the position");
                l.direction = glm::normalize(d);
            } else {
                o.where().key("direction").fail("a spot light needs a direction (or a target)");
            }
            if (auto v = o.get("inner_angle")) l.spot_inner_degrees = v->real(kSpotAngle);
            if (auto v = o.get("outer_angle")) l.spot_outer_degrees = v->real(kSpotAngle);
            if (l.spot_inner_degrees > l.spot_outer_degrees)
                o.where().key("inner_angle").fail("must not exceed outer_angle (" +
                                                  std::to_string(l.spot_outer_degrees) + ")");
        }
        o.finish();
        return l;
    }

    void read_environment(Object o) {
        Environment& env = scene_.environment;
        const auto color = o.get("color");
        const auto image = o.get("image");
        const auto scale = o.get("scale");
        const auto rotation = o.get("rotation");
        const auto importance = o.get("importance_sampled");
        o.finish();
        if (color && image) image->fail("give either color or image, not both");
        if (color) env.color = color->color(jsonf::kNonNegative);
        if (image) {
            env.image = resolve(file_, image->string());
            const bool exists = options_.file_exists ? options_.file_exists(env.image) : fs::is_regular_file(env.image);
            if (!exists) image->fail(env.image + ": no such file");
            try {
                check_file_allowed(env.image);  // read later by path, not through read_file
            } catch (const Error& e) {
                image->fail(e.what());
            }
        } else {
            for (const auto& v : {scale, rotation, importance})
                if (v) v->fail("only an environment image takes this field");
        }
        if (scale) env.scale = scale->real(jsonf::kNonNegative);
        if (rotation) env.rotation_degrees = rotation->real(Range{-36000, 36000});
        if (importance) env.importance_sampled = importance->boolean();
    }

    std::string file_;
    const LoadOptions& options_;
    Scene scene_;
    SceneBuilder builder_;
    std::map<std::string, std::uint32_t> material_index_;
    std::map<std::string, std::shared_ptr<ObjMesh>> meshes_;
};

}  // namespace

Scene parse_scene_file(const std::string& text, const std::string& file, const LoadOptions& options) {
    return SceneReader(file, options).read(text);
}

Scene obj_scene(const std::string& file, const LoadOptions& options) {
    const ObjMesh mesh = load_obj(file, options.read_file);
    Scene s;
    s.name = stem(file);
    s.warnings = mesh.warnings;
    if (mesh.triangle_count() == 0) throw Error(file + ": the mesh has no faces (an empty scene)");
    std::vector<std::uint32_t> index(mesh.materials.size());
    const std::vector<bool> used = used_materials(mesh);
    for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
        const ObjMaterial& om = mesh.materials[i];
        if (!used[i] && textured(om)) continue;
        if (om.defined) {
            index[i] = s.add_material(om.name, obj_material_with_textures(s, om, options));
            continue;
        }
        // As Blender and assimp load such a file: grey, with a warning.
        s.warnings.push_back(file + ":" + std::to_string(om.usemtl_line) + ": usemtl '" + om.name +
                             "': no .mtl file defines it; it is the default grey");
        index[i] = s.add_material(om.name, diffuse(glm::vec3(0.8f)));
    }
    std::vector<std::uint32_t> tri_mat(mesh.triangle_count());
    std::optional<std::uint32_t> grey;
    for (std::size_t t = 0; t < tri_mat.size(); ++t) {
        const int mi = mesh.triangle_material[t];
        if (mi >= 0) {
            tri_mat[t] = index[std::size_t(mi)];
        } else {
            if (!grey) grey = s.add_material("(default)", diffuse(glm::vec3(0.8f)));
            tri_mat[t] = *grey;
        }
    }
    SceneBuilder builder(s, options.max_triangles);
    VertexAttributes attr{&mesh.uvs, nullptr, &mesh.colors};
    builder.add(mesh.vertices, mesh.normals, glm::mat4(1), tri_mat, file, attr);
    builder.finish();
    if (s.triangle_count() == 0) throw Error(file + ": every triangle is degenerate (an empty scene)");

    present_bare_mesh(s, options.presentation);
    return s;
}

}  // namespace clpath
