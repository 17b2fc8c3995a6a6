#pragma once
// A glTF file's container and JSON, checked before tinygltf sees them:
// tinygltf converts JSON values by recursion (a 20,000-deep "extras" overflows
// the stack) and reads a field of the wrong type as its default (a light's
// "intensity": "bright" became 1). Each check names the file and the field.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace clpath::gltf {

// Deeper JSON is refused before any parser sees it. Real files nest about ten
// levels; "extras" written by tools rarely reach fifty.
constexpr std::size_t kMaxJsonDepth = 512;

// The deepest a node may sit below its scene's root.
constexpr std::size_t kMaxNodeDepth = 256;

// Throws clpath::Error "FILE: the JSON nests deeper than 512 levels (at byte N) ..."
// for text nesting arrays and objects deeper than max_depth.
void check_json_depth(std::string_view json, const std::string& file, std::size_t max_depth = kMaxJsonDepth);

// The JSON chunk of a .glb, after checking its 12-byte header (the magic, the
// version: 2; 1 is glTF 1.0's binary extension, refused as such; the length)
// and the first chunk's header. Throws clpath::Error naming the field.
std::string_view glb_json_chunk(const std::string& bytes, const std::string& file);

// The .glb with its JSON chunk replaced by `json` (padded to 4 bytes, as the
// container requires), the chunks after it kept as they are.
std::string glb_with_json(const std::string& bytes, const std::string& json);

// asset.version and asset.minVersion (2.x only; a 1.x document is refused as
// glTF 1.0, also when it has no asset but 1.0's dictionaries), and the
// required extensions (gltf_support.hpp). Returns the warnings for required
// extensions that only change the look.
std::vector<std::string> check_version_and_extensions(const nlohmann::json& doc, const std::string& file);

// Every field clpath reads, and the fields that decide what a file means
// (the default scene, camera projections, punctual lights): of the type and
// in the range the glTF 2.0 specification gives, and every index in range.
// Throws clpath::Error "FILE: PATH: what" for the first that is not.
void check_document(const nlohmann::json& doc, const std::string& file);

// After check_document: the node hierarchy below the scene's roots (the
// default scene's, or without scenes every node that is no other's child)
// has no cycle ("nodes[3]: the node is its own ancestor") and places at most
// max_placed nodes, counted without walking the paths (a node whose parents
// each list the same child twice, forty levels deep, has 2^40 paths).
// (LoadOptions::max_placed_nodes).
void check_node_hierarchy(const nlohmann::json& doc, const std::string& file, std::size_t max_placed);

// Skins, morph targets and animations are not evaluated: the meshes load in
// their rest pose (morph weights zero). One warning naming what the file has,
// or "" when it has none of them.
std::string rest_pose_warning(const nlohmann::json& doc, const std::string& file);

// Removes "skins" and every node's "skin"; true if there were any.
bool drop_skins(nlohmann::json& doc);

}  // namespace clpath::gltf
