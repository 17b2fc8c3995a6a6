// OBJ files as they come from other tools: what Blender and assimp load with
// a warning loads here with a warning; broken syntax is still an error.
#include <string>

#include <gtest/gtest.h>

#include "scene/memory_files.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene_file.hpp"

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

}  // namespace
}  // namespace clpath
