// libFuzzer target: the JSON scene parser. Any input must end in a Scene or a
// clpath::Error; anything else (a crash, a sanitizer report, another
// exception type escaping) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_files.hpp"
#include "scene/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        clpath::Scene s = clpath::parse_scene_file(text, "fuzz/scene.json", clpath::fuzz::options());
        // What the renderer relies on.
        if (s.vertices.size() != s.triangle_count() * 3) __builtin_trap();
        if (!s.normals.empty() && s.normals.size() != s.vertices.size()) __builtin_trap();
        for (auto m : s.triangle_material)
            if (m >= s.materials.size()) __builtin_trap();
        (void)clpath::camera_data(s.camera);
    } catch (const clpath::Error&) {
    }
    return 0;
}
