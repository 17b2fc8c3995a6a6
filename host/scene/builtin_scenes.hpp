#pragma once
// Scenes built in code, available without any file.
#include <cstddef>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

// The thesis renderer's Cornell box (docs/thesis-scene.md), with every
// surface diffuse: the default scene.
Scene cornell_thesis_scene();

// The triangle-count scaling scene: the thesis room (walls and lamp, all
// diffuse) around one bumpy UV sphere where the thesis's front sphere stands,
// with about `triangles` triangles in all (the sphere gets what the room
// leaves); the sphere's size on screen is the same whatever the count.
// Accepted counts: 100 to 50,000,000. Its name carries the actual count.
Scene scaling_scene(std::size_t triangles);

// A closed room (every ray from the camera hits something, as in the closed
// room + displaced sphere scenes of tinybvh's published traversal figures) around the same bumpy sphere as scaling_scene: six inward
// walls, a lamp under the ceiling and the sphere, about `triangles` in all.
// The camera is the thesis camera, now inside the room. Counts: 100 to 50,000,000.
Scene closed_room_scene(std::size_t triangles);

// Names accepted by builtin_scene() ("scaling:N" stands for every count N), and the scene for one of them (throws
// clpath::Error for an unknown name).
// "bunnies:N": N instances of the Stanford bunny (69,666 triangles, Debian's
// glmark2-data copy, kBunnyFile), stored once, on a square grid on a floor
// under a sky: each copy turned, scaled non-uniformly, every third one
// mirrored. 10,000 place 7 10^8 triangles in megabytes of device memory.
// Throws clpath::Error for N outside [1, 1000000] or the bunny file missing.
inline constexpr const char* kBunnyFile = "/usr/share/glmark2/models/bunny.obj";
Scene bunnies_scene(std::size_t instances);

// "city:N": a city at night lit by N small lamps (2 N emissive triangles) over
// its streets, in four colours of one power each, among 8 x 8 buildings of
// random heights (a fixed seed: the same city every time), no sky. Every lamp
// lights a few streets: picking lamps by power alone wastes most shadow rays.
// Counts: 1 to 1,000,000.
Scene night_city_scene(std::size_t lights);

std::vector<std::string> builtin_scene_names();
Scene builtin_scene(const std::string& name);

}  // namespace clpath
