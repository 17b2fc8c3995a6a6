#include <cstring>

#include "scene/gltf_parts.hpp"
#include "util/error.hpp"

namespace clpath::gltf {

void Source::fail(const std::string& path, const std::string& what) const {
    throw Error(file + ": " + path + ": " + what);
}

namespace {
int component_size(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

int type_components(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

std::string type_name(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "type " + std::to_string(type);
    }
}

template <class T>
T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
}  // namespace

float View::get(std::size_t i, int c) const {
    if (!data) return 0;
    const unsigned char* p = data + i * stride + std::size_t(c) * std::size_t(component_size(component_type));
    // Normalized integers: KHR glTF 2.0 section 3.11 (signed ones clamp at -1).
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p) / 65535.0f;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(load<std::int8_t>(p) / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(load<std::int16_t>(p) / 32767.0f, -1.0f);
    default: return 0;
    }
}

std::uint32_t View::index(std::size_t i) const {
    if (!data) return 0;
    const unsigned char* p = data + i * stride;
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
    default: return load<std::uint32_t>(p);
    }
}

View view(const Source& src, int index, const std::string& path, int type, int alt_type,
          const std::vector<int>& allowed, bool integers) {
    const auto& m = src.model;
    if (index < 0 || std::size_t(index) >= m.accessors.size())
        src.fail(path, "accessor " + std::to_string(index) + " does not exist (the file has " +
                           std::to_string(m.accessors.size()) + ")");
    const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
    View v;
    v.path = path;
    const std::string where = path + " (accessors[" + std::to_string(index) + "])";
    if (a.sparse.isSparse) src.fail(where, "sparse accessors are not supported");
    if (a.type != type && a.type != alt_type)
        src.fail(where, "expected " + type_name(type) + (alt_type >= 0 ? " or " + type_name(alt_type) : "") +
                            ", found " + type_name(a.type));
    bool ok = false;
    for (int t : allowed) ok = ok || t == a.componentType;
    if (!ok) src.fail(where, "component type " + std::to_string(a.componentType) + " is not allowed here");
    if (!integers && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
        src.fail(where, "integer components must be normalized here");
    v.component_type = a.componentType;
    v.components = type_components(a.type);
    v.normalized = a.normalized;
    v.count = a.count;
    const std::size_t elem = std::size_t(component_size(a.componentType)) * std::size_t(v.components);
    // A bound on what one accessor may claim, before count is multiplied by anything.
    const std::size_t max_count = std::size_t(3) * src.options.max_triangles + 2;
    if (a.count > max_count)
        src.fail(where, "count " + std::to_string(a.count) + " exceeds the limit of " + std::to_string(max_count));
    if (a.bufferView < 0) return v;  // all zeros
    if (std::size_t(a.bufferView) >= m.bufferViews.size())
        src.fail(where, "bufferView " + std::to_string(a.bufferView) + " does not exist (the file has " +
                            std::to_string(m.bufferViews.size()) + ")");
    const tinygltf::BufferView& bv = m.bufferViews[std::size_t(a.bufferView)];
    const std::string bv_path = "bufferViews[" + std::to_string(a.bufferView) + "]";
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
        src.fail(bv_path, "buffer " + std::to_string(bv.buffer) + " does not exist");
    const auto& data = m.buffers[std::size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        src.fail(bv_path, "bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                              " run past the end of buffers[" + std::to_string(bv.buffer) + "] (" +
                              std::to_string(data.size()) + " bytes)");
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) src.fail(bv_path, "byteStride " + std::to_string(v.stride) + " is less than an element");
    if (a.count > 0) {
        const std::size_t need = a.byteOffset + (a.count - 1) * v.stride + elem;  // bounded: count <= max_count
        if (a.byteOffset > bv.byteLength || need > bv.byteLength)
            src.fail(where, std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) +
                                " run past the end of " + bv_path + " (" + std::to_string(bv.byteLength) + " bytes)");
    }
    v.data = data.data() + bv.byteOffset + a.byteOffset;
    return v;
}

}  // namespace clpath::gltf
