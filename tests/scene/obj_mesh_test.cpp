// OBJ meshes and MTL materials: what is read, how MTL maps to clpath
// materials, and that every broken file is refused with FILE:LINE.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "scene/load/load_options.hpp"
#include "scene/memory_files.hpp"
#include "scene/load/obj_mesh.hpp"
#include "support/temp_paths.hpp"

namespace clpath {
namespace {

using test::error_of;
using test::MemoryFiles;

ObjMesh parse(const std::string& obj, const MemoryFiles& files = {}) {
    return parse_obj(obj, "m/mesh.obj", files.options().read_file);
}
std::string parse_error(const std::string& obj, const MemoryFiles& files = {}) {
    return error_of([&] { parse(obj, files); });
}

const char* kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ObjMesh, PolygonsAreTriangulated) {
    const ObjMesh m = parse(std::string(kSquare) + "f 1 2 3 4\n");
    EXPECT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.vertices.size(), 6u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_EQ(m.triangle_material[0], -1);
    // A pentagon: three triangles; negative (relative) indices work.
    const ObjMesh p = parse("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf -5 -4 -3 -2 -1\n");
    EXPECT_EQ(p.triangle_count(), 3u);
}

TEST(ObjMesh, KeepsVertexNormals) {
    const ObjMesh m = parse(std::string(kSquare) + "vn 0 0 1\nvn 0 0.6 0.8\nf 1//1 2//2 3//1\nf 1 3 4\n");
    ASSERT_EQ(m.normals.size(), 6u);
    EXPECT_EQ(m.normals[1], glm::vec3(0, 0.6f, 0.8f));
    EXPECT_EQ(m.normals[3], glm::vec3(0));  // the face without normals: zero, shaded flat later
}

TEST(ObjMesh, AcceptsTheUsualStatements) {
    const ObjMesh m = parse(
        "# comment\n\no thing\ng group\ns 1\nv 0 0 0 # trailing comment\nv 1 0 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
        "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1 2/2 3/3\nl 1 2\r\n");
    EXPECT_EQ(m.triangle_count(), 2u);
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0], "m/mesh.obj: 1 line and point elements ignored");
}

// Statements clpath does not use never reach tinyobjloader, which reads some
// of them unchecked: a skin weight (vw) with joint id 1e38 is an out-of-range
// float-to-int conversion in it, and a negative joint id makes it refuse the
// whole file. The mesh is the same as without them.
TEST(ObjMesh, UnusedStatementsNeverReachTheLibrary) {
    const std::string faces = "vn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n";
    const ObjMesh plain = parse(std::string(kSquare) + faces);
    const ObjMesh m = parse(std::string(kSquare) +
                            "vw 1 1e38 0.5\nvw 2 -1 0.5\nvp 0.5 0.5\nt crease 2/1 1 2 3\ns 99999999999\n"
                            "o 99999999999\ng a b\n" + faces + "vw 3 0 1 2 1e38\n");
    EXPECT_EQ(m.vertices, plain.vertices);
    EXPECT_EQ(m.normals, plain.normals);
    EXPECT_EQ(m.triangle_material, plain.triangle_material);
}

// Lines end where tinyobjloader ends them, at \n, \r or \r\n, so that the
// line check sees every statement the library sees: one after a lone \r is
// a statement of its own (also after a comment), checked and numbered.
TEST(ObjMesh, LoneCarriageReturnEndsALine) {
    EXPECT_EQ(parse("v 0 0 0\rv 1 0 0\r\nv 0 1 0\rf 1 2 3\r").triangle_count(), 1u);
    const std::string e = parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n# comment\rf 1 2 9\n");
    EXPECT_NE(e.find("m/mesh.obj:5: face: vertex index 9 is out of range"), std::string::npos) << e;
}

// --- MTL to clpath materials ------------------------------------------------------

Material material(const std::string& mtl) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl a\n" + mtl;
    const ObjMesh m = parse("mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", files);
    EXPECT_EQ(m.materials.size(), 1u);
    EXPECT_TRUE(m.materials.at(0).defined);
    EXPECT_EQ(m.triangle_material.at(0), 0);
    return m.materials.at(0).material;
}

TEST(ObjMaterials, DiffuseFromKd) {
    const Material m = material("Kd 0.5 0.25 0.125\nKs 0.1 0.1 0.1\nNs 50\nillum 2\n");
    EXPECT_EQ(m.kind, CLP_MAT_DIFFUSE);
    EXPECT_FLOAT_EQ(m.albedo[1], 0.25f);
}

TEST(ObjMaterials, EmissionFromKe) {
    const Material m = material("Kd 0 0 0\nKe 10 5 1\n");
    EXPECT_EQ(m.kind, CLP_MAT_DIFFUSE);
    EXPECT_FLOAT_EQ(m.emission[0], 10.0f);
    EXPECT_FLOAT_EQ(m.emission[2], 1.0f);
}

TEST(ObjMaterials, MetalFromPm) {
    const Material m = material("Kd 0.9 0.6 0.2\nPm 1\nPr 0.3\n");
    EXPECT_EQ(m.kind, CLP_MAT_CONDUCTOR);
    EXPECT_FLOAT_EQ(m.albedo[1], 0.6f);
    EXPECT_FLOAT_EQ(m.roughness, 0.3f);
}

TEST(ObjMaterials, ReflectiveIllumIsMirrorOrGlossy) {
    Material m = material("Ks 0.8 0.8 0.8\nillum 3\n");
    EXPECT_EQ(m.kind, CLP_MAT_MIRROR);
    EXPECT_FLOAT_EQ(m.albedo[0], 0.8f);
    m = material("Ks 0.8 0.8 0.8\nNs 30\nillum 3\n");
    EXPECT_EQ(m.kind, CLP_MAT_CONDUCTOR);
    EXPECT_NEAR(m.roughness, std::pow(2.0 / 32.0, 0.25), 1e-6);  // alpha = sqrt(2 / (Ns + 2)) = roughness^2
}

TEST(ObjMaterials, GlassFromIllumOrDissolve) {
    Material m = material("Ni 1.33\nillum 7\n");
    EXPECT_EQ(m.kind, CLP_MAT_DIELECTRIC);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    EXPECT_FLOAT_EQ(m.albedo[0], 1.0f);
    m = material("d 0.5\nTf 0.5 0.9 0.5\n");
    EXPECT_EQ(m.kind, CLP_MAT_DIELECTRIC);
    EXPECT_FLOAT_EQ(m.ior, 1.5f);  // no Ni: ordinary glass
    EXPECT_FLOAT_EQ(m.albedo[1], 0.9f);
}

TEST(ObjMaterials, OutOfRangeValuesNameFileMaterialAndKey) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl hot\nKd 1.5 0 0\n";
    EXPECT_EQ(parse_error("mtllib x.mtl\n", files), "m/x.mtl: material 'hot': Kd (1.5, 0, 0) is out of range (each must be in [0, 1])");
    files.files["m/x.mtl"] = "newmtl neg\nKe -1 0 0\n";
    EXPECT_NE(parse_error("mtllib x.mtl\n", files).find("m/x.mtl: material 'neg': Ke"), std::string::npos);
}

TEST(ObjMaterials, UnreadTextureMapsAreIgnoredWithAWarning) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl a\nKd 1 1 1\nmap_Ks shine.png\n";
    const ObjMesh m = parse("mtllib x.mtl\n", files);
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0], "m/mesh.obj: texture maps other than map_Kd and map_d in its materials are ignored");
}

TEST(ObjMaterials, DiffuseAndAlphaMapsMakeTheGltfMaterial) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl a\nKd 0.5 0.5 0.5\nNs 100\nPm 0.25\nmap_Kd tex/wood.png\nmap_d tex/mask.png\n";
    const ObjMesh m = parse("mtllib x.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                            "usemtl a\nf 1/1 2/2 3/3\n", files);
    ASSERT_EQ(m.materials.size(), 1u);
    const ObjMaterial& om = m.materials[0];
    EXPECT_EQ(om.material.kind, CLP_MAT_GLTF);
    EXPECT_EQ(om.material.alpha_mode, CLP_ALPHA_MASK);
    EXPECT_FLOAT_EQ(om.material.metallic, 0.25f);
    EXPECT_NEAR(om.material.roughness, std::pow(2.0 / 102.0, 0.25), 1e-6);
    EXPECT_EQ(om.diffuse_texture, "m/tex/wood.png");
    EXPECT_EQ(om.alpha_texture, "m/tex/mask.png");
    // vt v runs up, glTF's down: flipped. Vertex colours as given.
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[1], glm::vec2(1, 1));
    EXPECT_EQ(m.uvs[2], glm::vec2(0, 0));
    ASSERT_EQ(m.colors.size(), 3u);
    EXPECT_EQ(m.colors[1], glm::vec4(0, 1, 0, 1));
}

TEST(ObjMaterials, UsemtlBeforeMtllibAndUndefinedNames) {
    MemoryFiles files;
    files.files["m/x.mtl"] = "newmtl a\nKd 0.1 0.2 0.3\n";
    const ObjMesh m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\nmtllib x.mtl\n", files);
    ASSERT_EQ(m.materials.size(), 2u);
    EXPECT_EQ(m.materials[0].name, "a");
    EXPECT_TRUE(m.materials[0].defined);
    EXPECT_EQ(m.materials[1].name, "b");
    EXPECT_FALSE(m.materials[1].defined);
    EXPECT_EQ(m.materials[1].usemtl_line, 6);
    EXPECT_EQ(m.triangle_material, (std::vector<int>{0, 1}));
}

// --- bad OBJ files -----------------------------------------------------------------

TEST(ObjMeshBad, IndexOutOfRange) {
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 1 2 5\n"),
              "m/mesh.obj:5: face: vertex index 5 is out of range (4 vertices defined above this line)");
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 1 2 -5\n"),
              "m/mesh.obj:5: face: vertex index -5 is out of range (4 vertices defined above this line)");
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 0 1 2\n"),
              "m/mesh.obj:5: face: vertex index 0 is out of range (4 vertices defined above this line)");
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 1//1 2//1 3//1\n"),
              "m/mesh.obj:5: face: normal index 1 is out of range (0 normals defined above this line)");
    EXPECT_EQ(parse_error(std::string(kSquare) + "vt 0 0\nf 1/2 2/1 3/1\n"),
              "m/mesh.obj:6: face: texture coordinate index 2 is out of range (1 texture coordinate defined above "
              "this line)");
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 1 2 99999999999999999999\n"),
              "m/mesh.obj:5: face: '99999999999999999999' is not a vertex reference (v, v/vt, v//vn or v/vt/vn)");
    EXPECT_EQ(parse_error("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"),
              "m/mesh.obj:1: face: vertex index 1 is out of range (0 vertices defined above this line)");
}

TEST(ObjMeshBad, NonFiniteCoordinates) {
    EXPECT_EQ(parse_error("v 0 0 0\nv nan 0 0\n"), "m/mesh.obj:2: vertex: 'nan' is not a finite number");
    EXPECT_EQ(parse_error("v 0 0 0\nv 1 inf 0\n"), "m/mesh.obj:2: vertex: 'inf' is not a finite number");
    EXPECT_EQ(parse_error("v 0 0 1e999\n"), "m/mesh.obj:1: vertex: '1e999' is not a finite number");
    EXPECT_EQ(parse_error("v 0 0 1e39\n"), "m/mesh.obj:1: vertex: '1e39' is too large for a float");
    EXPECT_EQ(parse_error("v 0 0 zero\n"), "m/mesh.obj:1: vertex: 'zero' is not a number");
    EXPECT_EQ(parse_error("vn 0 nan 1\n"), "m/mesh.obj:1: normal: 'nan' is not a finite number");
}

TEST(ObjMeshBad, TooFewVerticesPerFaceOrCoordinates) {
    EXPECT_EQ(parse_error(std::string(kSquare) + "f 1 2\n"), "m/mesh.obj:5: face has 2 corners, at least 3 are needed");
    EXPECT_EQ(parse_error(std::string(kSquare) + "f\n"), "m/mesh.obj:5: face has 0 corners, at least 3 are needed");
    EXPECT_EQ(parse_error("v 1 2\n"), "m/mesh.obj:1: vertex needs at least 3 numbers, got 2");
}

TEST(ObjMesh, MissingMaterialLibraryIsAWarning) {
    const ObjMesh m = parse("# x\nmtllib nowhere.mtl\n");
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0], "m/mesh.obj:2: mtllib 'nowhere.mtl': m/nowhere.mtl: no such file; the materials it would "
                             "define are the default grey");
}

TEST(ObjMeshBad, BinaryGarbage) {
    EXPECT_EQ(parse_error(std::string("v 0 0 0\nv 1\0 0 0\n", 16)), "m/mesh.obj:2: contains a NUL byte (is this a text OBJ file?)");
}

TEST(ObjMeshBad, TheFileIsNamedWhenItCannotBeRead) {
    EXPECT_EQ(error_of([] { load_obj("/no/such/mesh.obj", read_text_file); }), "/no/such/mesh.obj: no such file");
}

// A million triangles must load in seconds (the bar a user loading a scanned mesh expects); a generated grid
// of 1,000,000 triangles is written to a temporary file and timed. The loader runs on one thread, so on an
// idle machine its CPU time is its wall time; CPU time is what is timed, so that other processes sharing
// the machine (a parallel test run, a build) cannot fail the test.
TEST(ObjMesh, MillionTrianglesLoadInSeconds) {
    const std::string path = test::temp_path("million.obj");
    {
        std::ofstream out(path);
        const int n = 708;  // 707 x 707 cells, 2 triangles each: 999,698 triangles
        char line[96];
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k) {
                std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", i / double(n), 0.01 * ((i * 7 + k * 3) % 11), k / double(n));
                out << line;
            }
        for (int i = 0; i + 1 < n; ++i)
            for (int k = 0; k + 1 < n; ++k) {
                const int a = i * n + k + 1, b = a + 1, c = a + n, d = c + 1;
                out << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
            }
    }
    const std::clock_t t0 = std::clock();  // this process's CPU time
    const ObjMesh m = load_obj(path, read_text_file);
    const double seconds = double(std::clock() - t0) / CLOCKS_PER_SEC;
    std::filesystem::remove(path);
    EXPECT_EQ(m.triangle_count(), 707u * 707u * 2u);
    std::printf("loaded %zu triangles in %.2f s of CPU time\n", m.triangle_count(), seconds);
    EXPECT_LT(seconds, 10.0);
}

}  // namespace
}  // namespace clpath
