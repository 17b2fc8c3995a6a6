#include "scene/load/obj_mesh.hpp"

#include "scene/load/load_options.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>

#include <tiny_obj_loader.h>

#include "scene/load/obj_text_encoding.hpp"
#include "scene/load/obj_tokens.hpp"
#include "scene/load/polygon_triangulation.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

namespace fs = std::filesystem;
using namespace obj_text;

// What the line-by-line check learns on the way.
struct Scan {
    std::size_t v = 0, vt = 0, vn = 0;
    std::size_t lines_points = 0;
    struct Named {
        std::string name;
        int line;
    };
    std::vector<Named> mtllibs;
    std::vector<Named> usemtl;  // first use of each name
    std::vector<int> empty_usemtl;  // lines of usemtl statements that name nothing
    // Every face's corner count, in file order: tinyobjloader keeps only the
    // count modulo 256 (an unsigned char), so a face of 300 corners would
    // take its neighbours' corners.
    std::vector<std::uint32_t> face_corners;
    // Lines whose numbers had text after them ("3.1+e2"), rewritten with the
    // numbers alone, which is what tinyobjloader is handed; the first one's
    // warning, and how many there were.
    std::map<int, std::string> rewritten;
    std::string trailing_text_warning;
    std::size_t trailing_text_count = 0;
    int first_mtllib_line = 0, first_usemtl_line = 0;
};

// Checks every statement tinyobjloader would read leniently: numbers must be
// finite numbers, faces need three corners, indices must name a vertex, normal
// or texture coordinate defined above them.
Scan scan_obj(const std::string& text, const std::string& file) {
    Scan s;
    int line_no = 0;
    std::size_t pos = 0;
    auto fail = [&](const std::string& what) -> void { throw Error(file + ":" + std::to_string(line_no) + ": " + what); };
    auto check_numbers = [&](std::string_view key, std::string_view rest, const char* what, std::size_t min_count) {
        std::size_t n = 0;
        std::string numbers(key);  // the line with each number's text alone
        bool rewrite = false;
        for (std::string_view tok = next_token(rest); !tok.empty() && tok[0] != '#'; tok = next_token(rest)) {
            double d;
            std::string_view number = tok;
            if (!parse_double(tok, d)) {
                // As assimp and Blender read it: the number it starts with, and a warning.
                const std::size_t len = parse_leading_double(tok, d);
                if (len == 0) fail(std::string(what) + ": '" + std::string(tok) + "' is not a number");
                number = tok.substr(0, len);
                rewrite = true;
                if (s.trailing_text_count++ == 0)
                    s.trailing_text_warning = file + ":" + std::to_string(line_no) + ": " + what + ": '" +
                                              std::string(tok) + "' is not a number; read as " + std::string(number) +
                                              ", the number it starts with, as assimp and Blender read it";
            }
            numbers += " ";
            numbers += number;
            if (!std::isfinite(d)) fail(std::string(what) + ": '" + std::string(tok) + "' is not a finite number");
            if (std::fabs(d) > 3.0e38) fail(std::string(what) + ": '" + std::string(tok) + "' is too large for a float");
            ++n;
        }
        if (n < min_count)
            fail(std::string(what) + " needs at least " + std::to_string(min_count) + " numbers, got " +
                 std::to_string(n));
        if (rewrite) s.rewritten[line_no] = std::move(numbers);
    };
    auto check_index = [&](std::string_view tok, std::string_view part, std::size_t defined, const char* kind,
                           const char* kinds) {
        long long i;
        if (!parse_int(part, i)) fail("face: '" + std::string(tok) + "' is not a vertex reference (v, v/vt, v//vn or v/vt/vn)");
        const long long n = (long long)defined;
        if (i == 0 || i > n || i < -n)
            fail("face: " + std::string(kind) + " index " + std::to_string(i) + " is out of range (" +
                 std::to_string(defined) + " " + (defined == 1 ? kind : kinds) + " defined above this line)");
    };
    while (pos < text.size()) {
        ++line_no;
        const std::string_view line = next_line(text, pos);
        if (line.find('\0') != std::string_view::npos) fail("contains a NUL byte (is this a text OBJ file?)");
        std::string_view rest = line;
        const std::string_view key = next_token(rest);
        if (key.empty() || key[0] == '#') continue;
        if (key == "v") {
            check_numbers(key, rest, "vertex", 3);
            ++s.v;
        } else if (key == "vn") {
            check_numbers(key, rest, "normal", 3);
            ++s.vn;
        } else if (key == "vt") {
            check_numbers(key, rest, "texture coordinate", 1);
            ++s.vt;
        } else if (key == "f") {
            std::size_t corners = 0;
            for (std::string_view tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
                if (tok[0] == '#') fail("face: a comment after a face's corners is not supported");
                std::string_view parts[3];
                std::size_t np = 0, start = 0;
                for (std::size_t k = 0; k <= tok.size(); ++k)
                    if (k == tok.size() || tok[k] == '/') {
                        if (np == 3) fail("face: '" + std::string(tok) + "' has more than three parts");
                        parts[np++] = tok.substr(start, k - start);
                        start = k + 1;
                    }
                check_index(tok, parts[0], s.v, "vertex", "vertices");
                if (np > 1 && !parts[1].empty()) check_index(tok, parts[1], s.vt, "texture coordinate", "texture coordinates");
                if (np > 2 && !parts[2].empty()) check_index(tok, parts[2], s.vn, "normal", "normals");
                if (np > 2 && parts[2].empty()) fail("face: '" + std::string(tok) + "' has an empty normal index");
                ++corners;
            }
            if (corners < 3)
                fail("face has " + std::to_string(corners) + " corner" + (corners == 1 ? "" : "s") +
                     ", at least 3 are needed");
            s.face_corners.push_back(std::uint32_t(corners));
        } else if (key == "mtllib") {
            bool any = false;
            for (std::string_view tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
                s.mtllibs.push_back({with_slashes(std::string(tok)), line_no});
                any = true;
            }
            if (!any) fail("mtllib names no file");
            if (!s.first_mtllib_line) s.first_mtllib_line = line_no;
        } else if (key == "usemtl") {
            const std::string name = name_of(rest);
            if (name.empty()) {
                s.empty_usemtl.push_back(line_no);
                continue;
            }
            bool seen = false;
            for (const auto& u : s.usemtl) seen = seen || u.name == name;
            if (!seen) s.usemtl.push_back({name, line_no});
            if (!s.first_usemtl_line) s.first_usemtl_line = line_no;
        } else if (key == "l" || key == "p") {
            ++s.lines_points;
        }
    }
    return s;
}

// The MTL statements that take numbers, checked as scan_obj checks the OBJ's:
// tinyobjloader would read "Ns abc" as 0.
void scan_mtl(const std::string& text, const std::string& file) {
    static const char* const kNumeric[] = {"Ka", "Kd", "Ks", "Ke", "Kt", "Tf", "Ni", "Ns", "d", "Tr",
                                           "illum", "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
    int line_no = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        ++line_no;
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) nl = text.size();
        std::string_view rest(text.data() + pos, nl - pos);
        pos = nl + 1;
        const std::string_view key = next_token(rest);
        bool numeric = false;
        for (const char* k : kNumeric) numeric = numeric || key == k;
        if (!numeric) continue;
        auto fail = [&](const std::string& what) {
            throw Error(file + ":" + std::to_string(line_no) + ": " + std::string(key) + ": " + what);
        };
        std::size_t n = 0;
        for (std::string_view tok = next_token(rest); !tok.empty() && tok[0] != '#'; tok = next_token(rest)) {
            if (tok == "spectral" || tok == "xyz") fail("the '" + std::string(tok) + "' form is not supported (give r g b)");
            double d;
            if (!parse_double(tok, d)) fail("'" + std::string(tok) + "' is not a number");
            if (!std::isfinite(d) || std::fabs(d) > 3.0e38) fail("'" + std::string(tok) + "' is not a finite number");
            if (key == "illum" && d != std::floor(d)) fail("'" + std::string(tok) + "' is not a whole number");
            ++n;
        }
        if (n == 0) fail("needs a number");
    }
}

// The line of `keyword` (map_Kd, map_d) in material `material`'s block of an
// MTL file, for messages about the file it names; 0 if not found.
int mtl_statement_line(const std::string& text, const std::string& material, std::string_view keyword) {
    int line_no = 0;
    bool inside = false;
    for (std::size_t pos = 0; pos < text.size();) {
        const std::string_view line = next_line(text, pos);
        ++line_no;
        std::string_view rest = line;
        const std::string_view key = next_token(rest);
        if (key == "newmtl") inside = name_of(rest) == material;
        else if (inside && key == keyword) return line_no;
    }
    return 0;
}

// tinyobjloader also parses statements clpath never uses (skin weights vw,
// vp, lines and points, tags, smoothing groups, object and group names),
// some unchecked: a vw joint id of 1e38 is converted to int out of range,
// which is undefined behaviour. It is handed only the statements clpath
// reads; every other line is emptied, so line numbers stay the same.
// tinyobjloader reads a usemtl name up to the first space, so each usemtl
// line is handed over naming its material by a key without spaces
// (key_of_name); one that names nothing is emptied (the faces after it keep
// the material before it, as in assimp).
// Lines in `rewritten` (by number) are handed over as given there.
std::string statements_clpath_reads(const std::string& text, const std::map<std::string, std::string>& key_of_name,
                                    const std::map<int, std::string>& rewritten) {
    std::string out;
    out.reserve(text.size());
    int line_no = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        const std::size_t start = pos;
        const std::string_view line = next_line(text, pos);
        ++line_no;
        if (auto it = rewritten.find(line_no); it != rewritten.end()) {
            out += it->second;
            out.append(text, start + line.size(), pos - start - line.size());
            continue;
        }
        std::string_view rest = line;
        const std::string_view key = next_token(rest);
        if (key == "usemtl") {
            const std::string name = name_of(rest);
            if (!name.empty()) out += "usemtl " + key_of_name.at(name);
            out.append(text, start + line.size(), pos - start - line.size());
            continue;
        }
        const bool used = key == "v" || key == "vn" || key == "vt" || key == "f" || key == "mtllib";
        const std::size_t from = used ? start : start + line.size();
        out.append(text, from, pos - from);
    }
    return out;
}

std::string fmt3(const tinyobj::real_t* v) {
    std::ostringstream o;
    o << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return o.str();
}

glm::vec3 vec(const tinyobj::real_t* v) { return {float(v[0]), float(v[1]), float(v[2])}; }

// The clpath material an MTL entry stands for; docs/scene-format.md lists the
// rules. The kind is chosen first; a value out of range is an error on a
// channel that kind reads, and a warning (the value ignored) on one it does
// not, as other tools read such files (Ni 0 on an opaque material).
SceneMaterial from_mtl(const tinyobj::material_t& m, const std::string& mtl_file, std::vector<std::string>& warnings) {
    const std::string where = mtl_file + ": material '" + m.name + "': ";
    const int illum = m.illum;
    // What decides the kind is always read, so always checked.
    auto in01 = [](double v) { return std::isfinite(v) && v >= 0 && v <= 1; };
    if (!in01(m.dissolve)) throw Error(where + "d " + std::to_string(m.dissolve) + " is out of range (must be in [0, 1])");
    if (!in01(m.metallic)) throw Error(where + "Pm " + std::to_string(m.metallic) + " is out of range (must be in [0, 1])");
    enum class Kind { Dielectric, Metal, Mirror, Diffuse };
    const Kind kind = (m.dissolve < 1 || illum == 4 || illum == 6 || illum == 7 || illum == 9) ? Kind::Dielectric
                      : m.metallic >= 0.5                                                    ? Kind::Metal
                      : (illum == 3 || illum == 5 || illum == 8)                             ? Kind::Mirror
                                                                                             : Kind::Diffuse;
    const bool rough_used = kind != Kind::Diffuse;
    auto report = [&](bool used, const std::string& what) {
        if (used) throw Error(where + what);
        warnings.push_back(where + what + "; the material does not use it, so it is ignored");
    };
    auto check3 = [&](const char* key, const tinyobj::real_t* v, double hi, bool used) {
        for (int i = 0; i < 3; ++i)
            if (!(std::isfinite(v[i]) && v[i] >= 0 && v[i] <= hi)) {
                report(used, std::string(key) + " " + fmt3(v) + " is out of range (each must be in [0, " +
                                 (hi > 1 ? std::string("inf") : "1") + "])");
                return false;
            }
        return true;
    };
    auto check1 = [&](const char* key, double v, double lo, double hi, bool lo_open, bool used) {
        if (std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi) return true;
        report(used, std::string(key) + " " + std::to_string(v) + " is out of range (must be in " +
                         (lo_open ? "(" : "[") + std::to_string(int(lo)) + ", " + (hi > 1 ? "inf" : "1") + "])");
        return false;
    };
    const bool kd_ok = check3("Kd", m.diffuse, 1, kind == Kind::Diffuse || kind == Kind::Metal);
    const bool ks_ok = check3("Ks", m.specular, 1, kind == Kind::Mirror);
    const bool tf_ok = check3("Tf", m.transmittance, 1, kind == Kind::Dielectric);
    check3("Ke", m.emission, 1e30, true);
    const bool ns_ok = check1("Ns", m.shininess, 0, 1e30, false, rough_used && kind != Kind::Dielectric);
    const bool ni_ok = check1("Ni", m.ior, 0, 1e30, true, kind == Kind::Dielectric);
    const bool pr_ok = check1("Pr", m.roughness, 0, 1, false, rough_used);

    // Pr if given; else a Phong exponent turned into GGX roughness by the usual
    // Beckmann match, alpha = sqrt(2 / (Ns + 2)), and roughness = sqrt(alpha).
    // Ns <= 1 is tinyobjloader's default (no Ns line) and Ns >= 1000 is a mirror.
    float roughness = pr_ok ? float(m.roughness) : 0.0f;
    if (roughness == 0 && ns_ok && m.shininess > 1 && m.shininess < 1000)
        roughness = float(std::pow(2.0 / (m.shininess + 2.0), 0.25));
    const glm::vec3 kd = kd_ok ? vec(m.diffuse) : glm::vec3(0.8f), ks = ks_ok ? vec(m.specular) : glm::vec3(0),
                    tf = tf_ok ? vec(m.transmittance) : glm::vec3(0);
    const bool has_ks = ks.x > 0 || ks.y > 0 || ks.z > 0;

    SceneMaterial out;
    switch (kind) {
    case Kind::Dielectric: {
        // Ni 1 is the MTL default, and a glass of index 1 would be invisible.
        const float ior = ni_ok && m.ior != 1 ? float(m.ior) : 1.5f;
        const bool has_tf = tf.x > 0 || tf.y > 0 || tf.z > 0;
        out = dielectric(ior, pr_ok ? float(m.roughness) : 0.0f, has_tf ? tf : glm::vec3(1));
        break;
    }
    case Kind::Metal:
        out = conductor(kd, roughness);
        break;
    case Kind::Mirror: {
        const glm::vec3 tint = has_ks ? ks : glm::vec3(1);
        out = roughness > 0 ? conductor(tint, roughness) : mirror(tint);
        break;
    }
    case Kind::Diffuse:
        out = diffuse(kd);
        break;
    }
    for (int i = 0; i < 3; ++i) out.emission[i] = float(m.emission[i]);
    return out;
}

// Texture maps clpath does not read (map_Kd and map_d it does).
bool has_texture(const tinyobj::material_t& m) {
    return !(m.ambient_texname.empty() && m.specular_texname.empty() &&
             m.specular_highlight_texname.empty() && m.bump_texname.empty() && m.displacement_texname.empty() &&
             m.reflection_texname.empty() && m.roughness_texname.empty() &&
             m.metallic_texname.empty() && m.sheen_texname.empty() && m.emissive_texname.empty() &&
             m.normal_texname.empty());
}

// Hands tinyobjloader the materials already read and checked, all at once, at
// the first mtllib it meets; later mtllib lines then add nothing.
class PreparedMaterials : public tinyobj::MaterialReader {
public:
    PreparedMaterials(const std::vector<tinyobj::material_t>& m, const std::map<std::string, int>& map)
        : materials_(m), map_(map) {}
    bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string*, std::string*) override {
        if (!given_) {
            *materials = materials_;
            *map = map_;
            given_ = true;
        }
        return true;
    }

private:
    const std::vector<tinyobj::material_t>& materials_;
    const std::map<std::string, int>& map_;
    bool given_ = false;
};

// material_t has no constructor; LoadMtl initialises one to the MTL defaults.
tinyobj::material_t blank_material() {
    std::vector<tinyobj::material_t> m;
    std::map<std::string, int> map;
    std::istringstream in("newmtl blank\n");
    std::string warn, err;
    tinyobj::LoadMtl(&map, &m, &in, &warn, &err);
    return m.at(0);
}

constexpr const char* kMaterialsTag = "__clpath_materials__";

}  // namespace

ObjMesh parse_obj(const std::string& raw_text, const std::string& file, const ReadFile& read_file) {
    const std::string text = obj_text_as_utf8(raw_text, file);
    const Scan scan = scan_obj(text, file);
    ObjMesh mesh;

    // Every library the file names is read and checked, whether or not
    // tinyobjloader would stop at the first one that loads.
    std::vector<tinyobj::material_t> tmats;
    std::map<std::string, int> tmap;
    const fs::path folder = fs::path(file).parent_path();
    bool textures = false;
    for (const auto& lib : scan.mtllibs) {
        const std::string path = (folder / lib.name).string();
        std::string mtl_text;
        try {
            mtl_text = read_file(path);
        } catch (const RestrictedFileError&) {
            throw;
        } catch (const Error& e) {
            // As Blender and assimp do: the mesh still loads, its materials grey.
            mesh.warnings.push_back(file + ":" + std::to_string(lib.line) + ": mtllib '" + lib.name + "': " +
                                    e.what() + "; the materials it would define are the default grey");
            continue;
        }
        mtl_text = obj_text_as_utf8(std::move(mtl_text), path);
        if (mtl_text.find('\0') != std::string::npos) throw Error(path + ": contains a NUL byte (is this an MTL file?)");
        scan_mtl(mtl_text, path);
        std::vector<tinyobj::material_t> got;
        std::map<std::string, int> got_map;
        std::istringstream in(mtl_text);
        std::string warn, err;
        tinyobj::LoadMtl(&got_map, &got, &in, &warn, &err);
        if (!err.empty()) throw Error(path + ": " + err);
        for (auto m : got) {
            m.name = name_of(m.name);  // tinyobjloader keeps the spaces after it
            if (tmap.count(m.name)) continue;  // the first definition wins, as in tinyobjloader
            ObjMaterial om;
            om.name = m.name;
            om.defined = true;
            om.material = from_mtl(m, path, mesh.warnings);
            if (!m.diffuse_texname.empty() || !m.alpha_texname.empty()) {
                // A textured surface: the glTF material, base colour from map_Kd
                // (Kd is the colour where the map is absent), metallic Pm,
                // roughness Pr or from Ns, cut out by map_d.
                const fs::path dir = fs::path(path).parent_path();
                auto resolve = [&](const std::string& n) {
                    return n.empty() ? n : (dir / with_slashes(n)).lexically_normal().string();
                };
                om.diffuse_texture = resolve(m.diffuse_texname);
                om.alpha_texture = resolve(m.alpha_texname);
                om.mtl_file = path;
                if (!om.diffuse_texture.empty()) om.diffuse_texture_line = mtl_statement_line(mtl_text, m.name, "map_Kd");
                if (!om.alpha_texture.empty()) om.alpha_texture_line = mtl_statement_line(mtl_text, m.name, "map_d");
                float rough = float(m.roughness);
                if (rough == 0) rough = m.shininess > 1 && m.shininess < 1000 ? float(std::pow(2.0 / (m.shininess + 2.0), 0.25)) : 1.0f;
                const glm::vec3 base = om.diffuse_texture.empty() ? vec(m.diffuse) : glm::vec3(1);
                SceneMaterial g = gltf_material(base, float(m.metallic), rough);
                for (int i = 0; i < 3; ++i) g.emission[i] = om.material.emission[i];
                if (!om.alpha_texture.empty()) g.alpha_mode = CLP_ALPHA_MASK;
                om.material = g;
            }
            textures = textures || has_texture(m);
            tmap[m.name] = int(tmats.size());
            tmats.push_back(m);
            mesh.materials.push_back(om);
        }
    }
    for (const auto& u : scan.usemtl) {
        auto it = tmap.find(u.name);
        if (it != tmap.end()) {
            if (!mesh.materials[it->second].usemtl_line) mesh.materials[it->second].usemtl_line = u.line;
            continue;
        }
        // A name no library defines: kept, so that the scene file may supply
        // it; scene_file reports it if it does not.
        ObjMaterial om;
        om.name = u.name;
        om.usemtl_line = u.line;
        tinyobj::material_t tm = blank_material();
        tm.name = u.name;
        tmap[u.name] = int(tmats.size());
        tmats.push_back(tm);
        mesh.materials.push_back(om);
    }
    if (textures) mesh.warnings.push_back(file + ": texture maps other than map_Kd and map_d in its materials are ignored");
    if (scan.trailing_text_count)
        mesh.warnings.push_back(scan.trailing_text_warning +
                                (scan.trailing_text_count > 1
                                     ? " (and " + std::to_string(scan.trailing_text_count - 1) + " more such numbers)"
                                     : std::string()));
    if (scan.lines_points)
        mesh.warnings.push_back(file + ": " + std::to_string(scan.lines_points) + " line and point elements ignored");

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> unused;
    std::string warn, err;
    for (int line : scan.empty_usemtl)
        mesh.warnings.push_back(file + ":" + std::to_string(line) +
                                ": usemtl names no material; ignored (the faces after it keep the material before it)");
    // tinyobjloader knows the materials by keys without spaces.
    std::map<std::string, int> tiny_map;
    std::map<std::string, std::string> key_of_name;
    for (const auto& [name, i] : tmap) {
        const std::string key = "m" + std::to_string(i);
        tiny_map[key] = i;
        key_of_name[name] = key;
    }
    PreparedMaterials reader(tmats, tiny_map);
    // tinyobjloader resolves usemtl when it reads it, so the materials must be
    // in before the first usemtl: a leading mtllib line of our own when the
    // file uses a material before naming a library (or names none).
    const bool need_tag = scan.first_usemtl_line && (!scan.first_mtllib_line || scan.first_usemtl_line < scan.first_mtllib_line);
    const std::string statements = statements_clpath_reads(text, key_of_name, scan.rewritten);
    std::istringstream in(need_tag ? std::string("mtllib ") + kMaterialsTag + "\n" + statements : statements);
    // Faces come whole (triangulate = false): tinyobjloader cuts a quad along
    // its shorter diagonal, which lies outside a concave one.
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &unused, &warn, &err, &in, &reader, false, false);
    if (!ok || !err.empty()) throw Error(file + ": " + (err.empty() ? "tinyobjloader could not read it" : err));
    if (attrib.vertices.size() != scan.v * 3 || attrib.normals.size() != scan.vn * 3)
        throw Error(file + ": internal: tinyobjloader read a different number of vertices than the line check");

    const std::size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3;
    const bool with_normals = nn > 0;
    const std::size_t nt = attrib.texcoords.size() / 2;
    const bool with_colors = attrib.colors.size() == attrib.vertices.size() &&
                             std::any_of(attrib.colors.begin(), attrib.colors.end(), [](tinyobj::real_t c) { return c != 1; });
    std::vector<glm::vec3> polygon;
    std::vector<std::array<std::size_t, 3>> cut;
    std::size_t face_no = 0;  // in file order, across shapes
    for (const auto& shape : shapes) {
        const auto& m = shape.mesh;
        std::size_t first = 0;
        for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            if (face_no >= scan.face_corners.size() || (scan.face_corners[face_no] & 0xFFu) != m.num_face_vertices[f])
                throw Error(file + ": internal: tinyobjloader read other faces than the line check");
            const std::size_t corners = scan.face_corners[face_no++];
            if (first + corners > m.indices.size()) throw Error(file + ": internal: tinyobjloader face list is short");
            const int mat = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (mat >= int(mesh.materials.size())) throw Error(file + ": internal: material id out of range");
            for (std::size_t c = 0; c < corners; ++c) {
                const tinyobj::index_t idx = m.indices[first + c];
                if (idx.vertex_index < 0 || std::size_t(idx.vertex_index) >= nv)
                    throw Error(file + ": internal: vertex index out of range after the line check");
            }
            auto corner_position = [&](std::size_t c) {
                return vec(&attrib.vertices[3 * std::size_t(m.indices[first + c].vertex_index)]);
            };
            polygon.clear();
            for (std::size_t c = 0; c < corners; ++c) polygon.push_back(corner_position(c));
            // Triangles, nearly every face of most files, skip the polygon cutter.
            static const std::vector<std::array<std::size_t, 3>> kTriangle{{0, 1, 2}};
            const std::vector<std::array<std::size_t, 3>>* tris = &kTriangle;
            if (corners != 3) {
                cut = triangulate_polygon(polygon);
                tris = &cut;
            }
            for (const auto& tri : *tris) {
                for (std::size_t c : tri) {
                    const tinyobj::index_t idx = m.indices[first + c];
                    mesh.vertices.push_back(polygon[c]);
                    if (nt > 0) {
                        const bool has = idx.texcoord_index >= 0 && std::size_t(idx.texcoord_index) < nt;
                        const tinyobj::real_t* t = has ? &attrib.texcoords[2 * std::size_t(idx.texcoord_index)] : nullptr;
                        mesh.uvs.push_back(t ? glm::vec2(float(t[0]), 1.0f - float(t[1])) : glm::vec2(0));
                    }
                    if (with_colors) {
                        const tinyobj::real_t* c = &attrib.colors[3 * std::size_t(idx.vertex_index)];
                        mesh.colors.push_back(glm::clamp(glm::vec4(float(c[0]), float(c[1]), float(c[2]), 1.0f), 0.0f, 1.0f));
                    }
                    if (with_normals) {
                        const bool has = idx.normal_index >= 0 && std::size_t(idx.normal_index) < nn;
                        mesh.normals.push_back(has ? vec(&attrib.normals[3 * std::size_t(idx.normal_index)])
                                                   : glm::vec3(0));
                    }
                }
                mesh.triangle_material.push_back(mat < 0 ? -1 : mat);
            }
            first += corners;
        }
        if (first != m.indices.size()) throw Error(file + ": internal: tinyobjloader face list is long");
    }
    if (face_no != scan.face_corners.size()) throw Error(file + ": internal: tinyobjloader read fewer faces than the line check");
    return mesh;
}

ObjMesh load_obj(const std::string& file, const ReadFile& read_file) { return parse_obj(read_file(file), file, read_file); }

}  // namespace clpath
