// libFuzzer target: the OBJ and MTL loader, through the bare-OBJ scene (so the
// placement, degenerate-triangle and camera code runs too). An input is an
// OBJ, optionally followed by a line "#MTL" and the text every mtllib reads.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_files.hpp"
#include "scene/load/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const auto split = input.find("\n#MTL\n");
    const std::string obj = input.substr(0, split);
    const std::string mtl = split == std::string::npos ? std::string() : input.substr(split + 6);
    clpath::LoadOptions o;
    o.read_file = [&](const std::string& path) { return path == "fuzz/mesh.obj" ? obj : mtl; };
    o.max_triangles = 100000;
    try {
        clpath::fuzz::check_scene(clpath::obj_scene("fuzz/mesh.obj", o));
    } catch (const clpath::Error&) {
    }
    return 0;
}
