#pragma once
// How a scene is loaded: where its files come from, and how big it may get.
#include <cstddef>
#include <functional>
#include <string>

#include "image/texture_io.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/load/presentation.hpp"
#include "util/error.hpp"

namespace clpath {

// The whole of a file on disk, or clpath::Error "PATH: no such file" (or
// "is a directory", "permission denied", ...).
std::string read_text_file(const std::string& path);

// Every scene, mesh, material, texture and environment file a load opens
// must then lie inside `dir` (--restrict-files, CLPATH_RESTRICT_FILES), after
// resolving "..", symbolic links and absolute paths: for services that load
// files from untrusted users. Throws clpath::UsageError if dir is not a
// folder. Empty: no restriction (the default; real asset trees reach
// outside their folder with "../").
void restrict_files_to(const std::string& dir);
// A file refused by that restriction: never taken as a missing file that a
// loader may warn about and go without.
struct RestrictedFileError : Error {
    using Error::Error;
};
// Throws clpath::Error "PATH: resolves to RESOLVED, outside DIR (--restrict-files)"
// for a path outside the folder given to restrict_files_to; read_text_file calls it.
void check_file_allowed(const std::string& path);

struct LoadOptions {
    // Where scene, mesh and material files come from: the disk, or for tests
    // and fuzzers an in-memory set of files.
    ReadFile read_file = read_text_file;
    // Whether a file that is only referenced (an environment image) exists.
    std::function<bool(const std::string&)> file_exists;  // empty: the disk
    // A scene with more triangles is refused before it is built: a bound on
    // memory for the loader, and far beyond what a device holds today.
    std::size_t max_triangles = 50'000'000;
    // The most nodes a glTF file's node hierarchy may place, counting a node
    // once per path that reaches it (a child listed by several parents, or
    // twice by one, is placed once for each): a bound on the walk's work and
    // memory, refused before the walk. Mesh instances are placed nodes, so it
    // bounds them too.
    std::size_t max_placed_nodes = 1'000'000;
    // Turns a texture file's bytes into texels (OpenImageIO); fuzzers swap in their own.
    std::function<TextureImage(const std::string& bytes, const std::string& name)> decode_texture = clpath::decode_texture;
    // Which camera of a glTF file to use: its name, or its index in the
    // file's cameras; empty: the first one the node hierarchy places.
    std::string gltf_camera;
    // How a bare mesh (no camera, no lights of its own) is presented.
    PresentationOptions presentation;
};

}  // namespace clpath
