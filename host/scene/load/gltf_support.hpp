#pragma once
// What clpath does not read in a glTF file, said by name: a glTF 1.0
// document (whose dictionaries tinygltf reads as nothing, or refuses with a
// message about something else), or an extension the file requires that
// clpath does not implement (Basis textures, say), whose data would
// otherwise fail as "invalid bufferView" or load as garbage.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace clpath::gltf {

// The extensions clpath implements (docs/scene-format.md, "glTF 2.0").
const std::vector<std::string>& supported_extensions();

// Required extensions clpath does not implement but can render without: they
// only change how materials look, and every material they touch keeps its
// core glTF 2.0 values (a shader technique, specular-glossiness, unlit,
// texture transforms, the PBR layers beyond the core model).
const std::vector<std::string>& look_only_extensions();

// After tinygltf has read the document: throws clpath::Error "FILE: glTF 1.0
// is not supported (glTF 2.0 is)" for asset.version 1.x, or "FILE:
// extensionsRequired: NAME is not supported ..." for a required extension
// clpath does not implement, unless it is a look-only one: those come back as
// warnings naming them.
std::vector<std::string> refuse_unsupported(const std::string& version, const std::vector<std::string>& required,
                                            const std::string& file);

// For a document without asset.version: throws the glTF 1.0 message above
// when it has glTF 1.0's structure (objects where glTF 2.0 has arrays).
void refuse_version_1_structure(const nlohmann::json& doc, const std::string& file);

// The warning for a triangle-list primitive whose corner count (its vertices,
// or its indices) is not a multiple of 3: its last, incomplete triangle is
// dropped, as assimp does (indices out of range stay an error).
std::string incomplete_triangle_warning(const std::string& file, const std::string& path, std::size_t corners);

// The warning for a point or line primitive: skipped, as an OBJ's points and
// lines are (clpath renders surfaces); a file with nothing else is refused.
std::string points_and_lines_warning(const std::string& file, const std::string& path);

}  // namespace clpath::gltf
