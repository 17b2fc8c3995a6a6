// OBJ files as they come from other tools: what Blender and assimp load with
// a warning loads here with a warning; broken syntax is still an error.
#include <string>

#include <gtest/gtest.h>

#include "scene/memory_files.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/load/scene_file.hpp"

namespace clpath {
namespace {

using test::error_of;
using test::MemoryFiles;

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

bool has_warning(const std::vector<std::string>& w, const std::string& text) {
    for (const auto& s : w)
        if (s == text) return true;
    return false;
}

TEST(ObjRealFiles, MissingLibraryAndUndefinedMaterialAreGrey) {
    MemoryFiles files;
    files.files["m/a.obj"] = std::string("mtllib gone.mtl\n") + kTriangle + "usemtl paint\nf 1 2 3\n";
    const Scene s = obj_scene("m/a.obj", files.options());
    EXPECT_TRUE(has_warning(s.warnings, "m/a.obj:1: mtllib 'gone.mtl': m/gone.mtl: no such file; the materials it "
                                        "would define are the default grey"));
    EXPECT_TRUE(has_warning(s.warnings, "m/a.obj:5: usemtl 'paint': no .mtl file defines it; it is the default grey"));
    const Material& m = s.materials[s.triangle_material[0]];
    EXPECT_EQ(m.kind, CLP_MAT_DIFFUSE);
    EXPECT_FLOAT_EQ(m.albedo[0], 0.8f);
}

TEST(ObjRealFiles, OutOfRangeValueOnAnUnusedChannelIsAWarning) {
    MemoryFiles files;
    // Ni 0 on an opaque material: the index of refraction is never used.
    files.files["m/x.mtl"] = "newmtl plastic\nKd 0.6 0.2 0.2\nNi 0\nTf 2 2 2\n";
    const ObjMesh m = parse_obj(std::string("mtllib x.mtl\n") + kTriangle + "usemtl plastic\nf 1 2 3\n", "m/mesh.obj",
                                files.options().read_file);
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].material.kind, CLP_MAT_DIFFUSE);
    EXPECT_FLOAT_EQ(m.materials[0].material.albedo[0], 0.6f);
    EXPECT_TRUE(has_warning(m.warnings, "m/x.mtl: material 'plastic': Ni 0.000000 is out of range (must be in (0, "
                                        "inf]); the material does not use it, so it is ignored"));
    EXPECT_EQ(m.warnings.size(), 2u);  // and Tf
    // On glass the same Ni is read, so it is an error.
    files.files["m/x.mtl"] = "newmtl glass\nd 0.5\nNi 0\n";
    EXPECT_EQ(error_of([&] { parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file); }),
              "m/x.mtl: material 'glass': Ni 0.000000 is out of range (must be in (0, inf])");
}

TEST(ObjRealFiles, MtlNumbersThatDoNotParseAreErrors) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl shiny\nKd 0.5 0.5 0.5\nNs abc\n";
    EXPECT_EQ(error_of([&] { parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file); }),
              "m/x.mtl:3: Ns: 'abc' is not a number");
    files.files["m/x.mtl"] = "newmtl a\nKd 0.5 nan 0.5\n";
    EXPECT_EQ(error_of([&] { parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file); }),
              "m/x.mtl:2: Kd: 'nan' is not a finite number");
    files.files["m/x.mtl"] = "newmtl a\nillum 2.5\n";
    EXPECT_EQ(error_of([&] { parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file); }),
              "m/x.mtl:2: illum: '2.5' is not a whole number");
    files.files["m/x.mtl"] = "newmtl a\nd\n";
    EXPECT_EQ(error_of([&] { parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file); }),
              "m/x.mtl:2: d: needs a number");
    // Texture options are not numbers of the material.
    files.files["m/x.mtl"] = "newmtl a\nKd 1 1 1\nmap_Kd -s 1 1 1 wood.png\n";
    EXPECT_NO_THROW(parse_obj("mtllib x.mtl\n", "m/mesh.obj", files.options().read_file));
}

// Material names with spaces (written by 3ds Max and LightWave): the whole
// rest of the usemtl and newmtl lines, trimmed, as assimp and Blender read them.
TEST(ObjRealFiles, MaterialNamesWithSpaces) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl Hard Shiny Plastic  \nKd 0.1 0.2 0.4\nnewmtl Hard\nKd 0.9 0.9 0.9\n";
    const ObjMesh m = parse_obj(std::string("mtllib x.mtl\n") + kTriangle +
                                    "usemtl  Hard Shiny Plastic \t\nf 1 2 3\nusemtl Hard\nf 1 3 2\n",
                                "m/mesh.obj", files.options().read_file);
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    ASSERT_EQ(m.triangle_count(), 2u);
    const ObjMaterial& a = m.materials[std::size_t(m.triangle_material[0])];
    EXPECT_EQ(a.name, "Hard Shiny Plastic");
    EXPECT_TRUE(a.defined);
    EXPECT_FLOAT_EQ(a.material.albedo[2], 0.4f);
    const ObjMaterial& b = m.materials[std::size_t(m.triangle_material[1])];
    EXPECT_EQ(b.name, "Hard");
    EXPECT_FLOAT_EQ(b.material.albedo[2], 0.9f);
}

// "usemtl" with no name (assimp's empty_mat.obj): ignored with a warning,
// the faces after it keep the material before it.
TEST(ObjRealFiles, UsemtlWithoutANameIsIgnored) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl red\nKd 1 0 0\n";
    const ObjMesh m = parse_obj(std::string("mtllib x.mtl\n") + kTriangle + "usemtl red\nf 1 2 3\nusemtl \nf 1 3 2\n",
                                "m/mesh.obj", files.options().read_file);
    EXPECT_TRUE(has_warning(m.warnings, "m/mesh.obj:7: usemtl names no material; ignored (the faces after it keep "
                                        "the material before it)"));
    ASSERT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.triangle_material[0], m.triangle_material[1]);
    EXPECT_EQ(m.materials[std::size_t(m.triangle_material[1])].name, "red");
}

// Windows paths: ".\wood.jpg" and "libs\x.mtl" name files beside and below the OBJ.
TEST(ObjRealFiles, BackslashesInPathsAreFolderSeparators) {
    MemoryFiles files;
    files.files["m/libs/x.mtl"] = "newmtl wood\nmap_Kd .\\img\\wood.jpg\n";
    const ObjMesh m = parse_obj(std::string("mtllib libs\\x.mtl\n") + kTriangle + "usemtl wood\nf 1 2 3\n",
                                "m/mesh.obj", files.options().read_file);
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_TRUE(m.materials[0].defined);
    EXPECT_EQ(m.materials[0].diffuse_texture, "m/libs/img/wood.jpg");
}

// Byte-order marks: UTF-8 with one, and UTF-16 either way round (assimp's
// box_UTF16BE.obj), read as the same mesh as plain text.
TEST(ObjRealFiles, Utf8AndUtf16WithByteOrderMarks) {
    const std::string text = std::string(kTriangle) + "usemtl caf\xC3\xA9\nf 1 2 3\n";
    auto utf16 = [&](bool big_endian) {
        std::string out = big_endian ? "\xFE\xFF" : "\xFF\xFE";
        // The text's one non-ASCII letter, U+00E9, as one UTF-16 unit.
        for (std::size_t i = 0; i < text.size(); ++i) {
            unsigned u = (unsigned char)text[i];
            if (u == 0xC3) u = 0xE9, ++i;
            const char hi = char(u >> 8), lo = char(u & 0xFF);
            out += big_endian ? std::string{hi, lo} : std::string{lo, hi};
        }
        return out;
    };
    for (const std::string& file : {"\xEF\xBB\xBF" + text, utf16(true), utf16(false)}) {
        const ObjMesh m = parse_obj(file, "m/mesh.obj", MemoryFiles().options().read_file);
        ASSERT_EQ(m.triangle_count(), 1u);
        EXPECT_EQ(m.vertices[1], glm::vec3(1, 0, 0));
        ASSERT_EQ(m.materials.size(), 1u);
        EXPECT_EQ(m.materials[0].name, "caf\xC3\xA9");
    }
    // The control: without its mark, UTF-16 is not text clpath can read.
    EXPECT_NE(error_of([&] { parse_obj(utf16(true).substr(2), "m/mesh.obj", MemoryFiles().options().read_file); })
                  .find("m/mesh.obj:1: contains a NUL byte"),
              std::string::npos);
    EXPECT_EQ(error_of([&] { parse_obj(utf16(false) + "x", "m/mesh.obj", MemoryFiles().options().read_file); }),
              "m/mesh.obj: UTF-16 text with an odd number of bytes (cut short?)");
}

// A number followed by other text ("3.1+e2" in assimp's number_formats.obj,
// a mistyped 3.1e+2): read as the number it starts with, as assimp and
// Blender read it, with a warning naming the first line. Text that starts
// with no number stays an error.
TEST(ObjRealFiles, NumbersWithTextAfterThemReadAsTheNumberTheyStartWith) {
    const ObjMesh m = parse_obj("v 0 0 0\nv 1e+2 2.e+1 3.1+e2\nv +1e -2.5x 0\nvn 0 0 1z\nf 1//1 2//1 3//1\n", "m/mesh.obj",
                                MemoryFiles().options().read_file);
    ASSERT_EQ(m.triangle_count(), 1u);
    EXPECT_EQ(m.vertices[1], glm::vec3(100, 20, 3.1f));
    EXPECT_EQ(m.vertices[2], glm::vec3(1, -2.5f, 0));  // "1e": tinyobjloader alone would read 0
    ASSERT_EQ(m.normals.size(), 3u);
    EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
    EXPECT_TRUE(has_warning(m.warnings, "m/mesh.obj:2: vertex: '3.1+e2' is not a number; read as 3.1, the number it "
                                        "starts with, as assimp and Blender read it (and 3 more such numbers)"));
    EXPECT_EQ(error_of([] { parse_obj("v 0 0 x1\n", "m/mesh.obj", MemoryFiles().options().read_file); }),
              "m/mesh.obj:1: vertex: 'x1' is not a number");
    EXPECT_EQ(error_of([] { parse_obj("v 0 0 1e999x\n", "m/mesh.obj", MemoryFiles().options().read_file); }),
              "m/mesh.obj:1: vertex: '1e999x' is not a finite number");
}

}  // namespace
}  // namespace clpath
