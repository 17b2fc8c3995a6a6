#pragma once
// A scene of diffuse surfaces lit by point lights, written for Embree's own
// example path tracer (Debian's embree-tools `pathtracer`): the mesh as OBJ
// with its MTL (Kd), and an Embree command script (.ecs, read with
// `pathtracer -c NAME.ecs`) that loads it and gives the camera, the image
// size, the point lights, the samples per pixel and the path length. So
// clpath's renderer, its built-in Embree path tracer (clpath bench path) and
// Embree's own can render one scene side by side.
#include <string>

#include "scene/scene.hpp"

namespace clpath {

struct EmbreeExport {
    std::string obj, mtl, ecs;
};

// stem: the name the three files share (the script loads stem.obj, the OBJ
// names stem.mtl). Throws clpath::Error naming what Embree's example would
// render differently: a material that is not diffuse, an emitter (its OBJ
// reader ignores Ke), shading normals, a light that is not a point light, an
// environment. The path length is the scene's max_depth: Embree's
// pathtracer, at path length D, samples the point lights from the same D
// vertices clpath's path integrator does at depth D (clpath traces one more
// ray per path, to the last vertex, where a point light adds nothing).
EmbreeExport export_embree_scene(const Scene& scene, const std::string& stem, const std::string& source);

}  // namespace clpath
