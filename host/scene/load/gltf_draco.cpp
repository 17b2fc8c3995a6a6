// KHR_draco_mesh_compression: a primitive's attributes and triangles stored
// as one Draco bitstream in a buffer view (the extension's README), decoded
// through Debian's libdraco. Draco returns its attributes dequantised
// (float positions, normals and texture coordinates for quantised ones); each
// is converted into the accessor's component type, with the accessor's
// `normalized` (as Babylon.js does by default), so that the rest of the
// loader reads it as it reads an uncompressed accessor, KHR_mesh_quantization
// included.
#include <cmath>
#include <limits>
#include <type_traits>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

#include "scene/load/gltf_parts.hpp"

namespace clpath::gltf {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

template <class T>
bool convert_all(const draco::PointAttribute& att, std::size_t points, int components, unsigned char* out) {
    T* o = reinterpret_cast<T*>(out);
    const std::size_t n = std::size_t(components);
    // Dequantised floats into a normalized integer accessor: Draco converts to
    // unsigned ones only; glTF's signed ones map [-1, 1] by the largest value
    // (KHR_mesh_quantization, as View::floats reads them back).
    if constexpr (std::is_integral_v<T>)
        if (att.normalized() && (att.data_type() == draco::DT_FLOAT32 || att.data_type() == draco::DT_FLOAT64)) {
            float v[4];
            const float lo = std::is_signed_v<T> ? -1.0f : 0.0f, top = float(std::numeric_limits<T>::max());
            for (std::size_t i = 0; i < points; ++i) {
                if (!att.ConvertValue<float>(att.mapped_index(draco::PointIndex(std::uint32_t(i))), std::int8_t(components), v))
                    return false;
                for (std::size_t c = 0; c < n; ++c) {
                    if (!(v[c] >= lo && v[c] <= 1.0f)) return false;  // NaN too
                    o[i * n + c] = T(std::lround(v[c] * top));
                }
            }
            return true;
        }
    for (std::size_t i = 0; i < points; ++i)
        if (!att.ConvertValue<T>(att.mapped_index(draco::PointIndex(std::uint32_t(i))), std::int8_t(components), o + i * n))
            return false;
    return true;
}

}  // namespace

std::optional<DracoPrimitive> decode_draco(const Source& src, const tinygltf::Primitive& p, const std::string& prim_path) {
    const auto ext = p.extensions.find(kExtension);
    if (ext == p.extensions.end()) return std::nullopt;
    const std::string path = prim_path + ".extensions." + kExtension;
    const tinygltf::Value& e = ext->second;
    if (!e.IsObject()) src.fail(path, "expected an object");
    if (p.mode >= 0 && p.mode != TINYGLTF_MODE_TRIANGLES)
        src.fail(prim_path + ".mode", "a Draco-compressed primitive must be a triangle list (mode 4), not mode " +
                                          std::to_string(p.mode));
    const int view_index = int(whole_field(src, e, "bufferView", path, 0, INT32_MAX));
    const Bytes bytes = buffer_view_bytes(src, view_index, path + ".bufferView");
    if (!e.Has("attributes") || !e.Get("attributes").IsObject())
        src.fail(path + ".attributes", "required: an object mapping attribute names to Draco attribute ids");
    const tinygltf::Value& attrs = e.Get("attributes");

    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
    const std::string where = path + " (bufferViews[" + std::to_string(view_index) + "], " + std::to_string(bytes.size) +
                              " bytes)";
    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) src.fail(where, "not Draco data: " + type.status().error_msg_string());
    if (type.value() != draco::TRIANGULAR_MESH) src.fail(where, "the Draco data is a point cloud, not a triangle mesh");
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok() || !decoded.value())
        src.fail(where, "the Draco data cannot be decoded (corrupt or truncated): " +
                            (decoded.ok() ? std::string("no mesh") : decoded.status().error_msg_string()));
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();

    // The caps accessors have (LoadOptions::max_triangles), on what Draco decoded.
    const std::size_t points = mesh->num_points(), faces = mesh->num_faces();
    const std::size_t max_count = std::size_t(3) * src.options.max_triangles + 2;
    if (points > max_count || faces > src.options.max_triangles)
        src.fail(where, std::to_string(faces) + " triangles over " + std::to_string(points) +
                            " points exceed the limit of " + std::to_string(src.options.max_triangles) + " triangles");
    DracoPrimitive out;
    out.corners.reserve(faces * 3);
    for (std::size_t f = 0; f < faces; ++f)
        for (const draco::PointIndex& c : mesh->face(draco::FaceIndex(std::uint32_t(f)))) {
            if (c.value() >= points)
                src.fail(where, "triangle " + std::to_string(f) + " names point " + std::to_string(c.value()) +
                                    ", but the data has " + std::to_string(points));
            out.corners.push_back(c.value());
        }

    for (const std::string& name : attrs.Keys()) {
        const std::string ap = path + ".attributes." + name;
        const int id = int(whole_field(src, attrs, name.c_str(), path + ".attributes", 0, INT32_MAX));
        const auto acc = p.attributes.find(name);
        if (acc == p.attributes.end())
            src.fail(ap, "the primitive has no accessor for " + name + " (its attributes must list every compressed one)");
        if (acc->second < 0 || std::size_t(acc->second) >= src.model.accessors.size())
            src.fail(prim_path + ".attributes." + name, "accessor " + std::to_string(acc->second) + " does not exist");
        const tinygltf::Accessor& a = src.model.accessors[std::size_t(acc->second)];
        const std::string a_path = "accessors[" + std::to_string(acc->second) + "]";
        const int att_id = mesh->GetAttributeIdByUniqueId(std::uint32_t(id));
        if (att_id < 0) src.fail(ap, "the Draco data has no attribute with id " + std::to_string(id));
        draco::PointAttribute& att = *mesh->attribute(att_id);
        const int components = type_components(a.type), size = component_size(a.componentType);
        if (components == 0 || size == 0) src.fail(a_path, "the accessor's type or component type is not one of a vertex attribute");
        if (att.num_components() != components)
            src.fail(ap, "the Draco attribute has " + std::to_string(int(att.num_components())) + " components, but " +
                             a_path + " has " + std::to_string(components));
        if (a.count != points)
            src.fail(a_path + ".count", std::to_string(a.count) + " differs from the " + std::to_string(points) +
                                            " points of the Draco data");
        for (std::size_t i = 0; i < points; ++i)
            if (att.mapped_index(draco::PointIndex(std::uint32_t(i))).value() >= att.size())
                src.fail(ap, "point " + std::to_string(i) + " names a value past the attribute's " +
                                 std::to_string(att.size()));
        att.set_normalized(a.normalized);
        std::vector<unsigned char> bytes_out(points * std::size_t(components) * std::size_t(size));
        bool ok = false;
        switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: ok = convert_all<std::int8_t>(att, points, components, bytes_out.data()); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: ok = convert_all<std::uint8_t>(att, points, components, bytes_out.data()); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: ok = convert_all<std::int16_t>(att, points, components, bytes_out.data()); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: ok = convert_all<std::uint16_t>(att, points, components, bytes_out.data()); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: ok = convert_all<std::uint32_t>(att, points, components, bytes_out.data()); break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT: ok = convert_all<float>(att, points, components, bytes_out.data()); break;
        default: break;
        }
        if (!ok)
            src.fail(ap, "a decoded value does not fit " + a_path + "'s component type " + std::to_string(a.componentType) +
                             (a.normalized ? " (normalized)" : ""));
        out.attributes[name] = std::move(bytes_out);
    }
    return out;
}

bool drop_draco_indices(nlohmann::json& doc) {
    bool changed = false;
    const auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return false;
    for (auto& m : *meshes) {
        if (!m.is_object() || !m.contains("primitives") || !m["primitives"].is_array()) continue;
        for (auto& p : m["primitives"]) {
            if (!p.is_object()) continue;
            const auto ext = p.find("extensions");
            if (ext != p.end() && ext->is_object() && ext->contains(kExtension)) changed = p.erase("indices") > 0 || changed;
        }
    }
    return changed;
}

void use_draco(const DracoPrimitive& d, const std::string& name, View& v) {
    const auto it = d.attributes.find(name);
    if (it == d.attributes.end()) return;
    v.data = it->second.data();
    v.stride = std::size_t(component_size(v.component_type)) * std::size_t(v.components);
}

}  // namespace clpath::gltf
