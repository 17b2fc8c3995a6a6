#include "scene/load/gltf_document.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "scene/load/gltf_support.hpp"
#include "util/error.hpp"

namespace clpath::gltf {
namespace {

using nlohmann::json;

std::uint32_t u32_at(const std::string& b, std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string kind_of(const json& v) {
    switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string (" + v.dump().substr(0, 40) + ")";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "a number (" + v.dump().substr(0, 40) + ")";
    }
}

struct Range {
    double lo = -HUGE_VAL, hi = HUGE_VAL;
    bool lo_open = false, hi_open = false;
    bool has(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
    std::string text() const {
        if (std::isinf(hi)) return std::string(lo_open ? "above " : "at least ") + number_text(lo);
        return (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
    }
};
const Range kAnyNumber{};
const Range kPositive{0, HUGE_VAL, true};
const Range kNonNegative{0, HUGE_VAL};
const Range kUnit{0, 1};

// The sizes of the document's arrays, for index checks, and the singular noun each index names.
struct Section {
    const char* name;
    const char* noun;
};
constexpr Section kSections[] = {{"scenes", "scene"},       {"nodes", "node"},         {"meshes", "mesh"},
                                 {"accessors", "accessor"}, {"bufferViews", "bufferView"}, {"buffers", "buffer"},
                                 {"materials", "material"}, {"textures", "texture"},   {"images", "image"},
                                 {"samplers", "sampler"},   {"cameras", "camera"},     {"skins", "skin"},
                                 {"animations", "animation"}};

class Checker {
public:
    Checker(const json& doc, const std::string& file) : doc_(doc), file_(file) {}

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw Error(file_ + ": " + path + ": " + what);
    }

    static std::string at(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
    static std::string item(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

    std::size_t count(const char* section) const {
        const auto it = doc_.find(section);
        return it != doc_.end() && it->is_array() ? it->size() : 0;
    }
    std::size_t light_count() const {
        const json* lights = find(doc_, "extensions");
        lights = lights && lights->is_object() ? find(*lights, "KHR_lights_punctual") : nullptr;
        lights = lights && lights->is_object() ? find(*lights, "lights") : nullptr;
        return lights && lights->is_array() ? lights->size() : 0;
    }

    static const json* find(const json& o, const char* key) {
        const auto it = o.find(key);
        return it == o.end() ? nullptr : &*it;
    }

    // o[key] when present (else null; a required one that is absent fails), of the JSON type asked for.
    const json* object(const json& o, const char* key, const std::string& path, bool required = false) const {
        return typed(o, key, path, required, json::value_t::object, "an object");
    }
    const json* array(const json& o, const char* key, const std::string& path, bool required = false) const {
        return typed(o, key, path, required, json::value_t::array, "an array");
    }
    const json* string(const json& o, const char* key, const std::string& path, bool required = false) const {
        return typed(o, key, path, required, json::value_t::string, "a string");
    }
    void boolean(const json& o, const char* key, const std::string& path) const {
        (void)typed(o, key, path, false, json::value_t::boolean, "true or false");
    }
    // A string from a fixed list.
    void choice(const json& o, const char* key, const std::string& path, const std::vector<std::string>& allowed,
                bool required = false) const {
        const json* v = string(o, key, path, required);
        if (!v) return;
        std::string list;
        for (const auto& a : allowed) {
            if (*v == a) return;
            list += (list.empty() ? "" : ", ") + a;
        }
        fail(at(path, key), "'" + v->get<std::string>().substr(0, 40) + "' is not one of " + list);
    }

    void number(const json& v, const std::string& path, const Range& r) const {
        if (!v.is_number()) fail(path, "expected a number, got " + kind_of(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(path, "must be a finite number");
        if (!r.has(d)) fail(path, number_text(d) + " is out of range (must be " + r.text() + ")");
    }
    const json* number(const json& o, const char* key, const std::string& path, const Range& r,
                       bool required = false) const {
        const json* v = present(o, key, path, required);
        if (v) number(*v, at(path, key), r);
        return v;
    }
    // An array of exactly n numbers (any length when n is 0).
    void numbers(const json& o, const char* key, const std::string& path, std::size_t n, const Range& r) const {
        const json* v = array(o, key, path);
        if (!v) return;
        if (n && v->size() != n)
            fail(at(path, key), "expected " + std::to_string(n) + " numbers, got " + std::to_string(v->size()));
        for (std::size_t i = 0; i < v->size(); ++i) number((*v)[i], item(at(path, key), i), r);
    }
    void integer(const json& v, const std::string& path, std::int64_t lo, std::int64_t hi) const {
        const bool whole = v.is_number_integer() || (v.is_number_float() && std::floor(v.get<double>()) == v.get<double>());
        if (!whole) fail(path, "expected a whole number, got " + kind_of(v));
        const double d = v.get<double>();
        if (d < double(lo) || d > double(hi))
            fail(path, number_text(d) + " is out of range (must be from " + std::to_string(lo) + " to " +
                           std::to_string(hi) + ")");
    }
    const json* integer(const json& o, const char* key, const std::string& path, std::int64_t lo, std::int64_t hi,
                        bool required = false) const {
        const json* v = present(o, key, path, required);
        if (v) integer(*v, at(path, key), lo, hi);
        return v;
    }
    // An index into the document's array `section`.
    void index(const json& v, const std::string& path, const char* section) const {
        integer(v, path, 0, INT32_MAX);
        const std::int64_t i = v.get<std::int64_t>();
        const std::size_t n = std::strcmp(section, "lights") == 0 ? light_count() : count(section);
        if (std::size_t(i) >= n)
            fail(path, noun(section) + " " + std::to_string(i) + " does not exist (the file has " + std::to_string(n) +
                           (std::strcmp(section, "lights") == 0 ? " in KHR_lights_punctual)" : ")"));
    }
    void index(const json& o, const char* key, const std::string& path, const char* section, bool required = false) const {
        if (const json* v = present(o, key, path, required)) index(*v, at(path, key), section);
    }
    void indices(const json& o, const char* key, const std::string& path, const char* section, bool required = false) const {
        const json* v = array(o, key, path, required);
        if (!v) return;
        for (std::size_t i = 0; i < v->size(); ++i) index((*v)[i], item(at(path, key), i), section);
    }

    // Each element of a top-level array, which must hold objects.
    template <class F>
    void each(const char* section, F f) const {
        const json* a = array(doc_, section, "");
        if (!a) return;
        for (std::size_t i = 0; i < a->size(); ++i) {
            const std::string p = item(section, i);
            if (!(*a)[i].is_object()) fail(p, "expected an object, got " + kind_of((*a)[i]));
            f((*a)[i], p);
        }
    }

private:
    const json& doc_;
    const std::string& file_;

    static std::string noun(const char* section) {
        for (const auto& s : kSections)
            if (std::strcmp(s.name, section) == 0) return s.noun;
        return std::strcmp(section, "lights") == 0 ? "light" : section;
    }
    const json* present(const json& o, const char* key, const std::string& path, bool required) const {
        const json* v = find(o, key);
        if (!v && required) fail(at(path, key), "required, but missing");
        return v;
    }
    const json* typed(const json& o, const char* key, const std::string& path, bool required, json::value_t type,
                      const char* what) const {
        const json* v = present(o, key, path, required);
        if (v && v->type() != type) fail(at(path, key), std::string("expected ") + what + ", got " + kind_of(*v));
        return v;
    }
};

void check_texture_info(const Checker& c, const json& o, const char* key, const std::string& path) {
    const json* t = c.object(o, key, path);
    if (!t) return;
    const std::string p = Checker::at(path, key);
    c.index(*t, "index", p, "textures", true);
    c.integer(*t, "texCoord", p, 0, 64);
    c.number(*t, "scale", p, kAnyNumber);
    c.number(*t, "strength", p, kUnit);
    if (const json* ext = c.object(*t, "extensions", p))
        if (const json* tt = c.object(*ext, "KHR_texture_transform", p + ".extensions")) {
            const std::string tp = p + ".extensions.KHR_texture_transform";
            c.numbers(*tt, "offset", tp, 2, kAnyNumber);
            c.number(*tt, "rotation", tp, kAnyNumber);
            c.numbers(*tt, "scale", tp, 2, kAnyNumber);
            c.integer(*tt, "texCoord", tp, 0, 64);
        }
}

void check_material(const Checker& c, const json& m, const std::string& p) {
    c.string(m, "name", p);
    if (const json* pbr = c.object(m, "pbrMetallicRoughness", p)) {
        const std::string pp = p + ".pbrMetallicRoughness";
        c.numbers(*pbr, "baseColorFactor", pp, 4, kAnyNumber);  // ranges: the material reader's
        c.number(*pbr, "metallicFactor", pp, kAnyNumber);
        c.number(*pbr, "roughnessFactor", pp, kAnyNumber);
        check_texture_info(c, *pbr, "baseColorTexture", pp);
        check_texture_info(c, *pbr, "metallicRoughnessTexture", pp);
    }
    for (const char* t : {"normalTexture", "occlusionTexture", "emissiveTexture"}) check_texture_info(c, m, t, p);
    c.numbers(m, "emissiveFactor", p, 3, kAnyNumber);
    c.string(m, "alphaMode", p);
    c.number(m, "alphaCutoff", p, kAnyNumber);
    c.boolean(m, "doubleSided", p);
    if (const json* ext = c.object(m, "extensions", p)) {
        const std::string ep = p + ".extensions";
        if (const json* s = c.object(*ext, "KHR_materials_emissive_strength", ep))
            c.number(*s, "emissiveStrength", ep + ".KHR_materials_emissive_strength", kAnyNumber);
        if (const json* s = c.object(*ext, "KHR_materials_ior", ep)) c.number(*s, "ior", ep + ".KHR_materials_ior", kAnyNumber);
    }
}

void check_camera(const Checker& c, const json& cam, const std::string& p) {
    c.choice(cam, "type", p, {"perspective", "orthographic"}, true);
    const std::string type = cam["type"].get<std::string>();
    if (type == "perspective") {
        const json& v = *c.object(cam, "perspective", p, true);
        const std::string pp = p + ".perspective";
        c.number(v, "yfov", pp, Range{0, M_PI, true, true}, true);
        c.number(v, "aspectRatio", pp, kPositive);
        const double znear = c.number(v, "znear", pp, kPositive, true)->get<double>();
        c.number(v, "zfar", pp, Range{znear, HUGE_VAL, true});  // absent: an infinite projection
    } else {
        const json& v = *c.object(cam, "orthographic", p, true);
        const std::string op = p + ".orthographic";
        for (const char* k : {"xmag", "ymag"}) {
            c.number(v, k, op, kAnyNumber, true);
            if (v[k].get<double>() == 0) c.fail(op + "." + k, "must not be zero");
        }
        const double znear = c.number(v, "znear", op, kNonNegative, true)->get<double>();
        c.number(v, "zfar", op, Range{znear, HUGE_VAL, true}, true);
    }
}

void check_light(const Checker& c, const json& l, const std::string& p) {
    c.choice(l, "type", p, {"point", "spot", "directional"}, true);
    c.numbers(l, "color", p, 3, kNonNegative);
    c.number(l, "intensity", p, kNonNegative);
    c.number(l, "range", p, kPositive);
    if (l["type"] == "spot") {
        const json* s = c.object(l, "spot", p);
        const std::string sp = p + ".spot";
        if (!s) return;
        const json* inner = c.number(*s, "innerConeAngle", sp, Range{0, M_PI / 2, false, true});
        c.number(*s, "outerConeAngle", sp, Range{inner ? inner->get<double>() : 0, M_PI / 2, true});
    }
}

void check_node(const Checker& c, const json& n, const std::string& p) {
    c.indices(n, "children", p, "nodes");
    c.index(n, "mesh", p, "meshes");
    c.index(n, "camera", p, "cameras");
    c.index(n, "skin", p, "skins");
    c.numbers(n, "matrix", p, 16, kAnyNumber);
    c.numbers(n, "translation", p, 3, kAnyNumber);
    c.numbers(n, "rotation", p, 4, kAnyNumber);
    c.numbers(n, "scale", p, 3, kAnyNumber);
    c.numbers(n, "weights", p, 0, kAnyNumber);
    if (const json* ext = c.object(n, "extensions", p))
        if (const json* l = c.object(*ext, "KHR_lights_punctual", p + ".extensions"))
            c.index(*l, "light", p + ".extensions.KHR_lights_punctual", "lights", true);
}

void check_mesh(const Checker& c, const json& m, const std::string& p) {
    const json& prims = *c.array(m, "primitives", p, true);
    for (std::size_t i = 0; i < prims.size(); ++i) {
        const std::string pp = Checker::item(p + ".primitives", i);
        const json& prim = prims[i];
        if (!prim.is_object()) c.fail(pp, "expected an object, got " + kind_of(prim));
        const json& attrs = *c.object(prim, "attributes", pp, true);
        for (const auto& [name, v] : attrs.items()) c.index(v, pp + ".attributes." + name, "accessors");
        c.index(prim, "indices", pp, "accessors");
        c.index(prim, "material", pp, "materials");
        c.integer(prim, "mode", pp, 0, 6);
        if (const json* targets = c.array(prim, "targets", pp))
            for (std::size_t t = 0; t < targets->size(); ++t) {
                const std::string tp = Checker::item(pp + ".targets", t);
                if (!(*targets)[t].is_object()) c.fail(tp, "expected an object, got " + kind_of((*targets)[t]));
                for (const auto& [name, v] : (*targets)[t].items()) c.index(v, tp + "." + name, "accessors");
            }
    }
}

void check_accessor(const Checker& c, const json& a, const std::string& p) {
    c.index(a, "bufferView", p, "bufferViews");
    c.integer(a, "byteOffset", p, 0, INT64_MAX);
    const std::int64_t type = c.integer(a, "componentType", p, 0, INT32_MAX, true)->get<std::int64_t>();
    if (!(type >= 5120 && type <= 5126 && type != 5124))
        c.fail(p + ".componentType", std::to_string(type) + " is not a glTF component type (5120, 5121, 5122, 5123, 5125, 5126)");
    c.boolean(a, "normalized", p);
    c.integer(a, "count", p, 1, INT64_MAX, true);
    c.choice(a, "type", p, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, true);
    c.numbers(a, "min", p, 0, kAnyNumber);
    c.numbers(a, "max", p, 0, kAnyNumber);
    c.object(a, "sparse", p);
}

}  // namespace

void check_json_depth(std::string_view json, const std::string& file, std::size_t max_depth) {
    std::size_t depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char ch = json[i];
        if (in_string) {
            if (ch == '\\') ++i;  // the escaped character cannot end the string
            else if (ch == '"') in_string = false;
        } else if (ch == '"') {
            in_string = true;
        } else if (ch == '[' || ch == '{') {
            if (++depth > max_depth)
                throw Error(file + ": the JSON nests arrays and objects deeper than " + std::to_string(max_depth) +
                            " levels (at byte " + std::to_string(i) +
                            "); clpath refuses it rather than risk its parser's recursion");
        } else if ((ch == ']' || ch == '}') && depth > 0) {
            --depth;
        }
    }
}

std::string_view glb_json_chunk(const std::string& b, const std::string& file) {
    if (b.size() < 12) throw Error(file + ": GLB header: the file is shorter than the 12-byte header");
    const std::uint32_t version = u32_at(b, 4), length = u32_at(b, 8);
    if (version == 1)
        throw Error(file + ": glTF 1.0 is not supported (glTF 2.0 is): the GLB header's version is 1; convert the file "
                    "to glTF 2.0 first");
    if (version != 2)
        throw Error(file + ": GLB header: version " + std::to_string(version) +
                    " is not supported (a binary glTF 2.0 file has version 2)");
    if (length != b.size())
        throw Error(file + ": GLB header: length " + std::to_string(length) + " does not match the file's " +
                    std::to_string(b.size()) + " bytes");
    if (b.size() < 20) throw Error(file + ": GLB: the file ends before its first chunk");
    const std::uint32_t chunk = u32_at(b, 12);
    if (b.compare(16, 4, "JSON") != 0) throw Error(file + ": GLB: the first chunk is not of type JSON");
    if (chunk > b.size() - 20)
        throw Error(file + ": GLB: the JSON chunk's length " + std::to_string(chunk) + " runs past the end of the file");
    return std::string_view(b).substr(20, chunk);
}

std::string glb_with_json(const std::string& b, const std::string& json_text) {
    std::string j = json_text;
    while (j.size() % 4) j += ' ';
    const std::size_t rest = 20 + std::size_t(u32_at(b, 12));
    const std::size_t after = ((rest + 3) / 4) * 4 <= b.size() ? ((rest + 3) / 4) * 4 : b.size();
    const std::size_t total = 20 + j.size() + (b.size() - after);
    auto u32 = [](std::size_t v) {
        const std::uint32_t x = std::uint32_t(v);
        return std::string(reinterpret_cast<const char*>(&x), 4);
    };
    return "glTF" + u32(2) + u32(total) + u32(j.size()) + "JSON" + j + b.substr(after);
}

std::vector<std::string> check_version_and_extensions(const json& doc, const std::string& file) {
    if (!doc.is_object()) throw Error(file + ": not a valid glTF 2.0 file: the JSON document is not an object");
    std::string version;
    const auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object() || !asset->contains("version")) {
        refuse_version_1_structure(doc, file);  // glTF 1.0's dictionaries name the cause
        throw Error(file + ": asset.version: required, but missing (a glTF 2.0 file has \"asset\": {\"version\": \"2.0\"})");
    }
    const json& v = (*asset)["version"];
    if (v.is_number() && v.get<double>() < 2) version = "1.0";  // some 1.0 exporters wrote a number
    else if (!v.is_string()) throw Error(file + ": asset.version: expected a string such as \"2.0\", got " + kind_of(v));
    else version = v.get<std::string>();
    std::vector<std::string> required;
    if (auto r = doc.find("extensionsRequired"); r != doc.end()) {
        if (!r->is_array()) throw Error(file + ": extensionsRequired: expected an array of names, got " + kind_of(*r));
        for (std::size_t i = 0; i < r->size(); ++i) {
            if (!(*r)[i].is_string())
                throw Error(file + ": extensionsRequired[" + std::to_string(i) + "]: expected a name, got " + kind_of((*r)[i]));
            required.push_back((*r)[i].get<std::string>());
        }
    }
    std::vector<std::string> warnings = refuse_unsupported(version, required, file);  // 1.x refused here
    auto major_minor = [](const std::string& s, int& major, int& minor) {
        return std::sscanf(s.c_str(), "%d.%d", &major, &minor) == 2;
    };
    int major = 0, minor = 0;
    if (!major_minor(version, major, minor) || major != 2)
        throw Error(file + ": asset.version: '" + version.substr(0, 40) +
                    "' is not supported (clpath reads glTF 2.0 files, asset.version \"2.x\")");
    if (auto mv = asset->find("minVersion"); mv != asset->end()) {
        int mmajor = 0, mminor = 0;
        if (!mv->is_string() || !major_minor(mv->get<std::string>(), mmajor, mminor))
            throw Error(file + ": asset.minVersion: expected a version such as \"2.0\", got " + kind_of(*mv));
        if (mmajor != 2 || mminor > 0)
            throw Error(file + ": asset.minVersion: '" + mv->get<std::string>().substr(0, 40) +
                        "' is not supported (clpath reads glTF 2.0)");
    }
    return warnings;
}

void check_document(const json& doc, const std::string& file) {
    const Checker c(doc, file);
    for (const char* list : {"extensionsUsed", "extensionsRequired"})
        if (const json* a = c.array(doc, list, ""))
            for (std::size_t i = 0; i < a->size(); ++i)
                if (!(*a)[i].is_string()) c.fail(Checker::item(list, i), "expected a name, got " + kind_of((*a)[i]));
    for (const auto& s : kSections) c.array(doc, s.name, "");
    if (const json* scene = Checker::find(doc, "scene")) c.index(*scene, "scene", "scenes");
    c.each("scenes", [&](const json& s, const std::string& p) { c.indices(s, "nodes", p, "nodes"); });
    c.each("nodes", [&](const json& n, const std::string& p) { check_node(c, n, p); });
    c.each("meshes", [&](const json& m, const std::string& p) { check_mesh(c, m, p); });
    c.each("accessors", [&](const json& a, const std::string& p) { check_accessor(c, a, p); });
    c.each("bufferViews", [&](const json& v, const std::string& p) {
        c.index(v, "buffer", p, "buffers", true);
        c.integer(v, "byteOffset", p, 0, INT64_MAX);
        c.integer(v, "byteLength", p, 1, INT64_MAX, true);
        c.integer(v, "byteStride", p, 4, 252);
    });
    c.each("buffers", [&](const json& b, const std::string& p) {
        c.integer(b, "byteLength", p, 1, INT64_MAX, true);
        c.string(b, "uri", p);
    });
    c.each("materials", [&](const json& m, const std::string& p) { check_material(c, m, p); });
    c.each("textures", [&](const json& t, const std::string& p) {
        c.index(t, "sampler", p, "samplers");
        c.index(t, "source", p, "images");
    });
    c.each("images", [&](const json& i, const std::string& p) {
        c.string(i, "uri", p);
        c.string(i, "mimeType", p);
        c.index(i, "bufferView", p, "bufferViews");
    });
    c.each("samplers", [&](const json& s, const std::string& p) {
        for (const char* k : {"magFilter", "minFilter", "wrapS", "wrapT"}) c.integer(s, k, p, 0, 65535);
    });
    c.each("cameras", [&](const json& cam, const std::string& p) { check_camera(c, cam, p); });
    c.each("skins", [&](const json& s, const std::string& p) {
        c.indices(s, "joints", p, "nodes", true);
        if (s["joints"].empty()) c.fail(p + ".joints", "a skin needs at least one joint");
        c.index(s, "skeleton", p, "nodes");
        c.index(s, "inverseBindMatrices", p, "accessors");
    });
    if (const json* ext = c.object(doc, "extensions", ""))
        if (const json* lp = c.object(*ext, "KHR_lights_punctual", "extensions")) {
            const std::string p = "extensions.KHR_lights_punctual";
            if (const json* lights = c.array(*lp, "lights", p))
                for (std::size_t i = 0; i < lights->size(); ++i) {
                    const std::string ip = Checker::item(p + ".lights", i);
                    if (!(*lights)[i].is_object()) c.fail(ip, "expected an object, got " + kind_of((*lights)[i]));
                    check_light(c, (*lights)[i], ip);
                }
        }
}

namespace {

// Placed nodes below each node, counted once per path and saturating past
// the limit; memoised, so shared children cost one visit.
class PathCounter {
public:
    PathCounter(const json& nodes, const std::string& file, std::size_t limit)
        : nodes_(nodes), file_(file), limit_(limit), state_(nodes.size(), 0), placed_(nodes.size(), 0) {}

    std::size_t placed(std::size_t n, std::size_t depth) {
        const std::string path = "nodes[" + std::to_string(n) + "]";
        if (depth > kMaxNodeDepth)
            throw Error(file_ + ": " + path + ": the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
        if (state_[n] == kDone) return placed_[n];
        if (state_[n] == kOnPath) throw Error(file_ + ": " + path + ": the node is its own ancestor (a cycle)");
        state_[n] = kOnPath;
        std::size_t total = 1;
        if (auto c = nodes_[n].find("children"); c != nodes_[n].end())
            for (const auto& child : *c) total = std::min(limit_ + 1, total + placed(child.get<std::size_t>(), depth + 1));
        state_[n] = kDone;
        return placed_[n] = total;
    }

private:
    static constexpr char kOnPath = 1, kDone = 2;
    const json& nodes_;
    const std::string& file_;
    std::size_t limit_;
    std::vector<char> state_;
    std::vector<std::size_t> placed_;
};

}  // namespace

void check_node_hierarchy(const json& doc, const std::string& file, std::size_t max_placed) {
    static const json kNone = json::array();
    const auto it = doc.find("nodes");
    const json& nodes = it == doc.end() ? kNone : *it;
    std::vector<std::size_t> roots;
    std::string roots_path = "nodes";
    const auto scenes = doc.find("scenes");
    if (scenes != doc.end() && !scenes->empty()) {
        const std::size_t si = doc.contains("scene") ? doc["scene"].get<std::size_t>() : 0;
        roots_path = "scenes[" + std::to_string(si) + "].nodes";
        if (auto n = (*scenes)[si].find("nodes"); n != (*scenes)[si].end())
            for (const auto& r : *n) roots.push_back(r.get<std::size_t>());
    } else {
        std::vector<bool> child(nodes.size(), false);
        for (const auto& n : nodes)
            if (auto c = n.find("children"); c != n.end())
                for (const auto& i : *c) child[i.get<std::size_t>()] = true;
        for (std::size_t i = 0; i < nodes.size(); ++i)
            if (!child[i]) roots.push_back(i);
        // Following parents from any node must then come back round.
        if (roots.empty() && !nodes.empty())
            throw Error(file + ": nodes: every node is another's child, so the hierarchy has a cycle and no root");
    }
    PathCounter counter(nodes, file, max_placed);
    std::size_t total = 0;
    for (std::size_t r : roots) {
        total = std::min(max_placed + 1, total + counter.placed(r, 0));
        if (total > max_placed)
            throw Error(file + ": " + roots_path + ": the node hierarchy places more than " + std::to_string(max_placed) +
                        " nodes (a node listed as a child by several parents, or twice by one, is placed once per path "
                        "to it, and nodes[" + std::to_string(r) + "] alone leads to more); the limit is " +
                        std::to_string(max_placed) + " placed nodes");
    }
}

std::string rest_pose_warning(const json& doc, const std::string& file) {
    auto count = [&](const char* section) {
        const auto it = doc.find(section);
        return it != doc.end() && it->is_array() ? it->size() : std::size_t(0);
    };
    std::size_t morphed = 0;
    if (auto meshes = doc.find("meshes"); meshes != doc.end())
        for (const auto& m : *meshes)
            if (auto prims = m.find("primitives"); prims != m.end())
                for (const auto& p : *prims)
                    if (p.contains("targets") && !p["targets"].empty()) ++morphed;
    std::string what;
    auto add = [&](std::size_t n, const char* one, const char* many) {
        if (n) what += (what.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
    };
    add(count("skins"), "skin", "skins");
    add(morphed, "primitive with morph targets", "primitives with morph targets");
    add(count("animations"), "animation", "animations");
    if (what.empty()) return "";
    return file + ": " + what + ": not evaluated; the meshes are loaded in their rest pose (bind pose, morph weights 0)";
}

bool drop_skins(json& doc) {
    bool any = doc.erase("skins") > 0;
    if (auto nodes = doc.find("nodes"); nodes != doc.end())
        for (auto& n : *nodes) any = n.erase("skin") > 0 || any;
    return any;
}

}  // namespace clpath::gltf
