#pragma once
// Wavefront OBJ meshes and their MTL materials, read through tinyobjloader.
// tinyobjloader is lenient (a bad number reads as 0, a bad index is skipped
// with a warning that names no line), so every line is checked here first and
// a fault is reported as "FILE:LINE: ...".
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace clpath {

// Reads a whole file named by a scene or mesh, or throws clpath::Error naming
// it. Tests and fuzzers give one that reads from memory.
using ReadFile = std::function<std::string(const std::string& path)>;

struct ObjMaterial {
    std::string name;
    bool defined = false;  // false: named by usemtl but by no .mtl file
    int usemtl_line = 0;   // the first usemtl naming it, for messages
    SceneMaterial material{};  // from the .mtl, when defined (docs/scene-format.md has the mapping)
    // map_Kd and map_d, resolved against the .mtl's folder; empty: none. A
    // material with either is the glTF material (CLP_MAT_GLTF) and its
    // texture slot is filled in by the scene that loads the images.
    std::string diffuse_texture, alpha_texture;
    // Where they are named, for messages: the .mtl and the lines of map_Kd, map_d.
    std::string mtl_file;
    int diffuse_texture_line = 0, alpha_texture_line = 0;
};

struct ObjMesh {
    std::vector<glm::vec3> vertices;  // 3 per triangle, polygons already triangulated
    // Empty when the file has no vertex normals; else 3 per triangle, and a zero
    // vector at a corner that has none (the triangle is then shaded flat).
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;    // empty, or 3 per triangle: vt with v flipped (row 0 at v = 0, as glTF)
    std::vector<glm::vec4> colors; // empty, or 3 per triangle: the "v x y z r g b" extension, alpha 1
    std::vector<int> triangle_material;  // index into materials; -1: before any usemtl
    std::vector<ObjMaterial> materials;
    std::vector<std::string> warnings;   // what was read but ignored (textures, lines, points)
    std::size_t triangle_count() const { return triangle_material.size(); }
};

// file names the mesh in messages, and its folder is where mtllib files are
// looked for (through read_file).
ObjMesh parse_obj(const std::string& text, const std::string& file, const ReadFile& read_file);

// The file's contents through read_file, then parse_obj.
ObjMesh load_obj(const std::string& file, const ReadFile& read_file);

}  // namespace clpath
