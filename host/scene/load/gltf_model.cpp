#include "scene/load/gltf_model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "scene/load/gltf_document.hpp"
#include "scene/load/gltf_parts.hpp"
#include "scene/load/gltf_support.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

namespace fs = std::filesystem;
using gltf::Source;
using gltf::View;

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;

std::string lower_extension(const std::string& file) {
    std::string e = fs::path(file).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

glm::mat4 node_matrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[std::size_t(i)]);  // column-major, as glm
        return m;
    }
    glm::mat4 m(1);
    if (n.translation.size() == 3)
        m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4) {
        glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
        const float len = glm::length(q);
        if (len > 0 && std::isfinite(len)) m = m * glm::mat4_cast(q / len);
    }
    if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

// Corner indices of the primitive's triangles (strips and fans converted as
// the specification's section 3.7.2.1 lists).
std::vector<std::uint32_t> triangle_corners(const Source& src, const tinygltf::Primitive& p, const std::string& path,
                                            std::size_t vertex_count, const std::optional<gltf::DracoPrimitive>& draco) {
    std::vector<std::uint32_t> idx;
    if (draco || p.indices >= 0) {
        const std::string where = draco ? path + ".extensions.KHR_draco_mesh_compression" : path + ".indices";
        if (draco) idx = draco->corners;  // Draco's faces
        else idx = gltf::view(src, p.indices, where, TINYGLTF_TYPE_SCALAR, -1, {kUByte, kUShort, kUInt}, true).indices();
        const auto bad = std::find_if(idx.begin(), idx.end(), [&](std::uint32_t i) { return i >= vertex_count; });
        if (bad != idx.end())
            src.fail(where, "index " + std::to_string(*bad) + " at position " + std::to_string(bad - idx.begin()) +
                                " is out of range (the primitive has " + std::to_string(vertex_count) + " vertices)");
    } else {
        idx.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) idx[i] = std::uint32_t(i);
    }
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    std::vector<std::uint32_t> out;
    switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
        // An incomplete last triangle is dropped, as assimp does (read_primitive warns).
        idx.resize(idx.size() - idx.size() % 3);
        return idx;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
        for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
            const bool odd = i % 2;
            out.insert(out.end(), {idx[i], idx[i + (odd ? 2 : 1)], idx[i + (odd ? 1 : 2)]});
        }
        return out;
    case TINYGLTF_MODE_TRIANGLE_FAN:
        for (std::size_t i = 1; i + 1 < idx.size(); ++i) out.insert(out.end(), {idx[i], idx[i + 1], idx[0]});
        return out;
    case TINYGLTF_MODE_POINTS:
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP:
        return {};  // skipped, as an OBJ's lines are; read_primitive warns
    default: src.fail(path + ".mode", "unknown primitive mode " + std::to_string(mode));
    }
}

// out[c] = element corners[c] of `values` (rows of T's float components).
template <class T>
void gather(const std::vector<float>& values, const std::vector<std::uint32_t>& corners, std::vector<T>& out) {
    static_assert(sizeof(T) == T::length() * sizeof(float));
    out.resize(corners.size());
    const std::size_t n = std::size_t(T::length());
    for (std::size_t c = 0; c < corners.size(); ++c) std::memcpy(&out[c], values.data() + corners[c] * n, sizeof(T));
}

GltfPrimitive read_primitive(const Source& src, const tinygltf::Primitive& p, const std::string& path) {
    GltfPrimitive out;
    out.path = path;
    const auto attr = [&](const char* name) {
        auto it = p.attributes.find(name);
        return it == p.attributes.end() ? -1 : it->second;
    };
    const std::string ap = path + ".attributes.";
    const int pos_i = attr("POSITION");
    if (pos_i < 0) src.fail(ap + "POSITION", "a primitive needs positions");
    // KHR_draco_mesh_compression: the attributes it holds, and the triangles, come from its data.
    const std::optional<gltf::DracoPrimitive> draco = gltf::decode_draco(src, p, path);
    const auto view = [&](int i, const char* name, int type, int alt_type, const std::vector<int>& allowed,
                          bool plain_integers = false) {
        View v = gltf::view(src, i, ap + name, type, alt_type, allowed, false, plain_integers);
        if (draco) gltf::use_draco(*draco, name, v);
        return v;
    };
    // The component types are KHR_mesh_quantization's (a superset of the core's).
    const View pos = view(pos_i, "POSITION", TINYGLTF_TYPE_VEC3, -1, {kFloat, kByte, kUByte, kShort, kUShort}, true);
    const std::size_t n = pos.count;
    auto same_count = [&](const View& v) {
        if (v.count != n)
            src.fail(v.path, std::to_string(v.count) + " elements, but POSITION has " + std::to_string(n));
        return v;
    };
    std::optional<View> nrm, tan, uv, col;
    if (int i = attr("NORMAL"); i >= 0)
        nrm = same_count(view(i, "NORMAL", TINYGLTF_TYPE_VEC3, -1, {kFloat, kByte, kShort}));
    if (int i = attr("TANGENT"); i >= 0)
        tan = same_count(view(i, "TANGENT", TINYGLTF_TYPE_VEC4, -1, {kFloat, kByte, kShort}));
    if (int i = attr("TEXCOORD_0"); i >= 0)
        uv = same_count(view(i, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, -1, {kFloat, kByte, kUByte, kShort, kUShort}, true));
    if (int i = attr("COLOR_0"); i >= 0)
        col = same_count(view(i, "COLOR_0", TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4, {kFloat, kUByte, kUShort}));
    if (p.material >= 0 && std::size_t(p.material) >= src.model.materials.size())
        src.fail(path + ".material", "material " + std::to_string(p.material) + " does not exist (the file has " +
                                         std::to_string(src.model.materials.size()) + ")");
    out.material = p.material;

    const std::vector<std::uint32_t> corners = triangle_corners(src, p, path, n, draco);
    if (p.mode >= TINYGLTF_MODE_POINTS && p.mode <= TINYGLTF_MODE_LINE_STRIP)
        out.warning = gltf::points_and_lines_warning(src.file, path);
    if (p.mode < 0 || p.mode == TINYGLTF_MODE_TRIANGLES) {
        const std::size_t listed = draco ? corners.size() : p.indices >= 0 ? src.model.accessors[std::size_t(p.indices)].count : n;
        if (listed % 3) out.warning = gltf::incomplete_triangle_warning(src.file, path, listed);
    }
    // Each attribute decoded once per vertex, then gathered per corner.
    gather(pos.floats(3), corners, out.vertices);
    if (nrm) gather(nrm->floats(3), corners, out.normals);
    if (tan) gather(tan->floats(4), corners, out.tangents);
    if (uv) gather(uv->floats(2), corners, out.uvs);
    if (col) gather(col->floats(4, 1.0f), corners, out.colors);  // RGB gets alpha 1
    return out;
}

PunctualLight read_light(const Source& src, int index, const glm::mat4& world, const std::string& path) {
    if (index < 0 || std::size_t(index) >= src.model.lights.size())
        src.fail(path, "light " + std::to_string(index) + " does not exist (the file has " +
                           std::to_string(src.model.lights.size()) + " in KHR_lights_punctual)");
    const tinygltf::Light& gl = src.model.lights[std::size_t(index)];
    const std::string lp = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
    PunctualLight l;
    glm::vec3 color(1);
    if (gl.color.size() == 3) color = glm::vec3(gl.color[0], gl.color[1], gl.color[2]);
    const float intensity = float(gl.intensity);
    if (!(intensity >= 0) || !std::isfinite(intensity) || !(glm::all(glm::greaterThanEqual(color, glm::vec3(0)))))
        src.fail(lp, "colour and intensity must be finite and non-negative");
    // Candela (point, spot) and lux (directional) map to clpath's W/sr and W/m^2 one to one.
    l.intensity = color * intensity;
    l.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    const glm::vec3 axis = glm::vec3(world * glm::vec4(0, 0, -1, 0));  // lights shine down their local -z
    if (!(glm::length(axis) > 0)) src.fail(path, "the node's transform flattens the light's direction");
    l.direction = glm::normalize(axis);
    if (gl.type == "point") {
        l.type = PunctualLight::Type::Point;
    } else if (gl.type == "directional") {
        l.type = PunctualLight::Type::Directional;
    } else if (gl.type == "spot") {
        l.type = PunctualLight::Type::Spot;
        l.spot_inner_degrees = float(glm::degrees(gl.spot.innerConeAngle));
        l.spot_outer_degrees = float(glm::degrees(gl.spot.outerConeAngle));
        if (!(l.spot_inner_degrees >= 0 && l.spot_inner_degrees <= l.spot_outer_degrees && l.spot_outer_degrees <= 90))
            src.fail(lp + ".spot", "cone angles must satisfy 0 <= innerConeAngle <= outerConeAngle <= pi/2");
    } else {
        src.fail(lp + ".type", "unknown light type '" + gl.type + "' (point, spot or directional)");
    }
    return l;
}

Camera read_camera(const Source& src, int index, const glm::mat4& world, const std::string& path) {
    const tinygltf::Camera& gc = src.model.cameras[std::size_t(index)];
    const std::string cp = "cameras[" + std::to_string(index) + "]";
    Camera c;
    c.eye = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    c.target = c.eye + glm::vec3(world * glm::vec4(0, 0, -1, 0));  // cameras look down their local -z, +y up
    c.up = glm::vec3(world * glm::vec4(0, 1, 0, 0));
    c.width = 640;
    c.height = 480;
    if (gc.type == "orthographic") {
        // xmag and ymag are the view's half-extents; their ratio is the image's aspect.
        const double xmag = std::fabs(gc.orthographic.xmag), ymag = std::fabs(gc.orthographic.ymag);
        c.ortho_half_height = float(ymag);
        if (xmag > 0 && ymag > 0) c.height = std::clamp(int(std::lround(640.0 * ymag / xmag)), 1, 16384);
    } else {
        c.vfov_degrees = float(glm::degrees(gc.perspective.yfov));
        if (gc.perspective.aspectRatio > 0 && std::isfinite(gc.perspective.aspectRatio))
            c.height = std::clamp(int(std::lround(640.0 / gc.perspective.aspectRatio)), 1, 16384);
    }
    try {
        (void)camera_data(c);
    } catch (const Error& e) {
        src.fail(cp + " (placed by " + path + ")", e.what());
    }
    return c;
}

}  // namespace

std::size_t GltfModel::triangle_count() const {
    std::size_t n = 0;
    for (const auto& inst : instances)
        for (const auto& p : meshes[inst.mesh]) n += p.vertices.size() / 3;
    return n;
}

bool is_gltf_file(const std::string& file) {
    const std::string e = lower_extension(file);
    return e == ".gltf" || e == ".glb";
}

namespace {
GltfModel read_gltf(const std::string& bytes, const std::string& file, const LoadOptions& options);
}  // namespace

GltfModel load_gltf(const std::string& file, const LoadOptions& options) {
    return read_gltf(options.read_file(file), file, options);
}

namespace {
GltfModel read_gltf(const std::string& bytes, const std::string& file, const LoadOptions& options) {
    if (bytes.size() > 0xffffffffu) throw Error(file + ": larger than 4 GiB");
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    gltf::DataUris data_uris;
    const std::string text = binary ? std::string() : gltf::extract_data_uris(bytes, data_uris);
    const std::string_view json_text = binary ? gltf::glb_json_chunk(bytes, file) : std::string_view(text);
    // Everything tinygltf would take on trust is checked on the raw document
    // first; one that does not parse is left to tinygltf to report.
    gltf::check_json_depth(json_text, file);
    GltfModel out;
    std::string rewritten;  // the document tinygltf reads, when it differs from the file's
    {
        nlohmann::json doc = nlohmann::json::parse(json_text.begin(), json_text.end(), nullptr, false);
        if (!doc.is_discarded()) {
            out.warnings = gltf::check_version_and_extensions(doc, file);
            gltf::check_document(doc, file);
            gltf::check_node_hierarchy(doc, file, options.max_placed_nodes);
            for (auto& w : gltf::check_uris(doc, file, options, data_uris)) out.warnings.push_back(std::move(w));
            if (auto w = gltf::rest_pose_warning(doc, file); !w.empty()) out.warnings.push_back(w);
            // Skins are not animated here, so they are dropped before tinygltf,
            // which refuses one without inverseBindMatrices (optional in the
            // specification); the meshes stay in their rest pose. Meshopt's
            // fallback buffers, which hold no data, get a stand-in; Draco's
            // primitives take their triangles from the Draco data.
            bool changed = gltf::drop_skins(doc);
            changed = gltf::stand_in_fallback_buffers(doc, binary, data_uris) || changed;
            changed = gltf::drop_draco_indices(doc) || changed;
            if (changed) {
                rewritten = doc.dump();
                if (binary) rewritten = gltf::glb_with_json(bytes, rewritten);
            }
        }
    }

    tinygltf::TinyGLTF loader;
    gltf::Files files{&options, {}, &data_uris};
    loader.SetFsCallbacks(gltf::file_callbacks(files));
    loader.SetImageLoader(gltf::keep_encoded, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string dir = fs::path(file).parent_path().string();
    const std::string& given = rewritten.empty() ? (binary ? bytes : text) : rewritten;
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(given.data()),
                                                         unsigned(given.size()), dir)
                           : loader.LoadASCIIFromString(&model, &err, &warn, given.data(), unsigned(given.size()), dir);
    if (!ok || !err.empty()) {
        std::string what = err.empty() ? warn : err;
        while (!what.empty() && std::isspace(static_cast<unsigned char>(what.back()))) what.pop_back();
        throw Error(file + ": not a valid glTF 2.0 file: " + (what.empty() ? "unknown error" : what));
    }
    const Source src{model, file, options};

    gltf::read_materials(src, out);

    // Meshes are read once, however often nodes place them.
    out.meshes.resize(model.meshes.size());
    std::vector<bool> mesh_read(model.meshes.size(), false);
    std::size_t triangles = 0;
    struct CameraUse {
        int camera;
        glm::mat4 world;
        std::string node;
    };
    std::vector<CameraUse> cameras;
    std::vector<int> depth_of(model.nodes.size(), -1);  // on the current path: a cycle
    std::function<void(int, const glm::mat4&, std::size_t, const std::string&)> visit =
        [&](int ni, const glm::mat4& parent, std::size_t depth, const std::string& from) {
            const std::string path = "nodes[" + std::to_string(ni) + "]";
            if (ni < 0 || std::size_t(ni) >= model.nodes.size())
                src.fail(from, "node " + std::to_string(ni) + " does not exist (the file has " +
                                   std::to_string(model.nodes.size()) + ")");
            if (depth > gltf::kMaxNodeDepth)
                src.fail(path, "the node hierarchy is deeper than " + std::to_string(gltf::kMaxNodeDepth));
            if (depth_of[std::size_t(ni)] >= 0) src.fail(path, "the node is its own ancestor (a cycle)");
            depth_of[std::size_t(ni)] = int(depth);
            const tinygltf::Node& n = model.nodes[std::size_t(ni)];
            const glm::mat4 world = parent * node_matrix(n);
            if (n.mesh >= 0) {
                if (std::size_t(n.mesh) >= model.meshes.size())
                    src.fail(path + ".mesh", "mesh " + std::to_string(n.mesh) + " does not exist (the file has " +
                                                 std::to_string(model.meshes.size()) + ")");
                const std::size_t mi = std::size_t(n.mesh);
                if (!mesh_read[mi]) {
                    const auto& prims = model.meshes[mi].primitives;
                    for (std::size_t p = 0; p < prims.size(); ++p) {
                        out.meshes[mi].push_back(read_primitive(
                            src, prims[p], "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(p) + "]"));
                        GltfPrimitive& prim = out.meshes[mi].back();
                        if (prim.material >= 0)
                            if (const auto& t = out.materials[std::size_t(prim.material)].uv_transform)
                                for (glm::vec2& uv : prim.uvs) uv = glm::vec2(*t * glm::vec3(uv, 1));
                        if (!out.meshes[mi].back().warning.empty()) out.warnings.push_back(out.meshes[mi].back().warning);
                    }
                    mesh_read[mi] = true;
                }
                for (const auto& p : out.meshes[mi]) triangles += p.vertices.size() / 3;
                if (triangles > options.max_triangles)
                    src.fail(path, "the file's triangles exceed the limit of " + std::to_string(options.max_triangles) +
                                       " for one scene");
                out.instances.push_back({mi, world, path});
            }
            if (n.camera >= 0) {
                if (std::size_t(n.camera) >= model.cameras.size())
                    src.fail(path + ".camera", "camera " + std::to_string(n.camera) + " does not exist");
                cameras.push_back({n.camera, world, path});
            }
            if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
                const tinygltf::Value& v = it->second;
                if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber())
                    src.fail(path + ".extensions.KHR_lights_punctual", "expected {\"light\": index}");
                out.lights.push_back(read_light(src, v.Get("light").GetNumberAsInt(), world,
                                                path + ".extensions.KHR_lights_punctual.light"));
            }
            for (std::size_t c = 0; c < n.children.size(); ++c)
                visit(n.children[c], world, depth + 1, path + ".children[" + std::to_string(c) + "]");
            depth_of[std::size_t(ni)] = -1;
        };

    std::vector<int> roots;
    std::string roots_path;
    if (!model.scenes.empty()) {
        const int si = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (std::size_t(si) >= model.scenes.size()) src.fail("scene", "scene " + std::to_string(si) + " does not exist");
        roots = model.scenes[std::size_t(si)].nodes;
        roots_path = "scenes[" + std::to_string(si) + "].nodes";
    } else {
        // No scene: every node that is no other's child is a root.
        std::vector<bool> child(model.nodes.size(), false);
        for (const auto& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && std::size_t(c) < child.size()) child[std::size_t(c)] = true;
        for (std::size_t i = 0; i < child.size(); ++i)
            if (!child[i]) roots.push_back(int(i));
        roots_path = "nodes";
    }
    for (std::size_t r = 0; r < roots.size(); ++r)
        visit(roots[r], glm::mat4(1), 0, roots_path + "[" + std::to_string(r) + "]");

    if (!options.gltf_camera.empty()) {
        const std::string& want = options.gltf_camera;
        const bool numeric = std::all_of(want.begin(), want.end(), [](unsigned char c) { return std::isdigit(c); });
        const CameraUse* found = nullptr;
        for (const auto& c : cameras)
            if (!found && (model.cameras[std::size_t(c.camera)].name == want ||
                           (numeric && want.size() < 9 && c.camera == std::stoi(want))))
                found = &c;
        if (!found) {
            std::string names;
            for (std::size_t i = 0; i < model.cameras.size(); ++i)
                names += (names.empty() ? "" : ", ") + std::to_string(i) +
                         (model.cameras[i].name.empty() ? "" : " '" + model.cameras[i].name + "'");
            throw UnknownGltfCamera(file + ": no camera '" + want + "' placed by a node" +
                        (names.empty() ? " (the file has no cameras)" : " (cameras: " + names + ")"));
        }
        out.camera = read_camera(src, found->camera, found->world, found->node);
    } else if (!cameras.empty()) {
        out.camera = read_camera(src, cameras[0].camera, cameras[0].world, cameras[0].node);
    }
    if (!warn.empty()) out.warnings.push_back(file + ": " + warn);
    return out;
}

}  // namespace

}  // namespace clpath
