#pragma once
// A scene of diffuse and emissive surfaces written as a Wavefront OBJ mesh,
// its MTL materials, and a clpath scene file (JSON) that places the mesh:
// camera, render settings, and what MTL cannot say (two-sided emitters, the
// environment colour). Another renderer (Blender Cycles, through
// benchmarks/references/cycles_reference.py) reads the three to render the
// same image; `clpath render` reads the JSON back.
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

struct ObjExport {
    std::string obj, mtl, json;
};

// The mesh as OBJ (shared vertices, the faces' winding kept) and its MTL
// (Kd reflectance, Ke radiance), whatever the materials are: the exporters
// below refuse first what their readers would model differently. names: the
// MTL name of each scene material the mesh uses ("" for the others).
struct ObjMeshText {
    std::string obj, mtl;
    std::vector<std::string> names;
};
ObjMeshText obj_mesh_text(const Scene& scene, const std::string& stem, const std::string& source);

// stem: the file name the three share, without folder or extension (the OBJ
// names stem.mtl, the JSON stem.obj). Throws clpath::Error naming what another
// renderer would model differently: a material that is not diffuse (mirror,
// conductor, glass), shading normals, punctual lights, an environment image.
ObjExport export_obj_scene(const Scene& scene, const std::string& stem, const std::string& source);

}  // namespace clpath
