#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "scene/load/gltf_parts.hpp"
#include "util/error.hpp"

namespace clpath::gltf {

void Source::fail(const std::string& path, const std::string& what) const {
    throw Error(file + ": " + path + ": " + what);
}

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

std::int64_t whole_field(const Source& src, const tinygltf::Value& o, const char* key, const std::string& path,
                         std::int64_t lo, std::int64_t hi, std::optional<std::int64_t> absent) {
    const std::string at = path + "." + key;
    if (!o.Has(key)) {
        if (absent) return *absent;
        src.fail(at, "required, but missing");
    }
    const tinygltf::Value& v = o.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
    if (!std::isfinite(d) || std::floor(d) != d) src.fail(at, "expected a whole number");
    // Compared as doubles: a value past int64's range must not be converted first.
    if (d < double(lo) || d > double(hi))
        src.fail(at, std::to_string(std::int64_t(std::clamp(d, -9e18, 9e18))) + " is out of range (must be from " +
                         std::to_string(lo) + " to " + std::to_string(hi) + ")");
    return std::int64_t(d);
}

std::string string_field(const Source& src, const tinygltf::Value& o, const char* key, const std::string& path,
                         std::optional<std::string> absent) {
    if (!o.Has(key)) {
        if (absent) return *absent;
        src.fail(path + "." + key, "required, but missing");
    }
    if (!o.Get(key).IsString()) src.fail(path + "." + key, "expected a string");
    return o.Get(key).Get<std::string>();
}

namespace {
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

// Elements of component type T, each `from` components read and mapped by
// `convert`, into rows of `width` floats.
template <class T, class Convert>
void decode_rows(const View& v, int width, float* out, Convert convert) {
    const std::size_t from = std::size_t(v.components);
    if constexpr (std::is_same_v<T, float>) {
        if (v.stride == sizeof(float) * from && std::size_t(width) == from) {
            std::memcpy(out, v.data, v.count * from * sizeof(float));  // tightly packed floats: one copy
            return;
        }
    }
    for (std::size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        for (std::size_t c = 0; c < from; ++c) out[i * std::size_t(width) + c] = convert(load<T>(p + c * sizeof(T)));
    }
}
}  // namespace

std::vector<float> View::floats(int width, float fill) const {
    std::vector<float> out(count * std::size_t(width), 0.0f);
    if (width > components)
        for (std::size_t i = 0; i < count; ++i)
            for (int c = components; c < width; ++c) out[i * std::size_t(width) + std::size_t(c)] = fill;
    if (!data) return out;  // no buffer view: the accessor's own components are zeros
    float* o = out.data();
    if (!normalized && component_type != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        // KHR_mesh_quantization's unnormalized integers: their values as they are
        // (the node's transform or a texture transform scales them back).
        switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: decode_rows<std::uint8_t>(*this, width, o, [](std::uint8_t x) { return float(x); }); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: decode_rows<std::uint16_t>(*this, width, o, [](std::uint16_t x) { return float(x); }); break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: decode_rows<std::int8_t>(*this, width, o, [](std::int8_t x) { return float(x); }); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: decode_rows<std::int16_t>(*this, width, o, [](std::int16_t x) { return float(x); }); break;
        default: break;
        }
        return out;
    }
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: decode_rows<float>(*this, width, o, [](float x) { return x; }); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        decode_rows<std::uint8_t>(*this, width, o, [](std::uint8_t x) { return x / 255.0f; });
        break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        decode_rows<std::uint16_t>(*this, width, o, [](std::uint16_t x) { return x / 65535.0f; });
        break;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        decode_rows<std::int8_t>(*this, width, o, [](std::int8_t x) { return std::max(x / 127.0f, -1.0f); });
        break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        decode_rows<std::int16_t>(*this, width, o, [](std::int16_t x) { return std::max(x / 32767.0f, -1.0f); });
        break;
    default: break;
    }
    return out;
}

std::vector<std::uint32_t> View::indices() const {
    std::vector<std::uint32_t> out(count, 0u);
    if (!data) return out;
    auto copy = [&](auto type_tag) {
        using T = decltype(type_tag);
        for (std::size_t i = 0; i < count; ++i) out[i] = load<T>(data + i * stride);
    };
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: copy(std::uint8_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: copy(std::uint16_t{}); break;
    default:
        if (stride == sizeof(std::uint32_t)) std::memcpy(out.data(), data, count * sizeof(std::uint32_t));
        else copy(std::uint32_t{});
    }
    return out;
}

Bytes buffer_view_bytes(const Source& src, int index, const std::string& referrer) {
    const auto& m = src.model;
    if (index < 0 || std::size_t(index) >= m.bufferViews.size())
        src.fail(referrer, "bufferView " + std::to_string(index) + " does not exist (the file has " +
                               std::to_string(m.bufferViews.size()) + ")");
    const tinygltf::BufferView& bv = m.bufferViews[std::size_t(index)];
    if (const std::vector<unsigned char>* decoded = meshopt_view(src, index)) return {decoded->data(), decoded->size()};
    const std::string bv_path = "bufferViews[" + std::to_string(index) + "]";
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
        src.fail(bv_path, "buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::string b_path = "buffers[" + std::to_string(bv.buffer) + "]";
    if (is_fallback_buffer(m.buffers[std::size_t(bv.buffer)]))
        src.fail(bv_path, b_path + " is an EXT_meshopt_compression fallback buffer, which holds no data: only "
                                   "compressed views may name it");
    const auto& data = m.buffers[std::size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        src.fail(bv_path, "bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                              " run past the end of " + b_path + " (" + std::to_string(data.size()) + " bytes)");
    return {data.data() + bv.byteOffset, bv.byteLength};
}

View view(const Source& src, int index, const std::string& path, int type, int alt_type,
          const std::vector<int>& allowed, bool integers, bool plain_integers) {
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
    if (!integers && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized && !plain_integers)
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
    const Bytes bytes = buffer_view_bytes(src, a.bufferView, where);
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) src.fail(bv_path, "byteStride " + std::to_string(v.stride) + " is less than an element");
    if (a.count > 0) {
        const std::size_t need = a.byteOffset + (a.count - 1) * v.stride + elem;  // bounded: count <= max_count
        if (a.byteOffset > bytes.size || need > bytes.size)
            src.fail(where, std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) +
                                " run past the end of " + bv_path + " (" + std::to_string(bytes.size) + " bytes)");
    }
    v.data = bytes.data + a.byteOffset;
    return v;
}

}  // namespace clpath::gltf
