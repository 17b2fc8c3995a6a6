// libFuzzer target: the JSON scene parser. Any input must end in a Scene or a
// clpath::Error; anything else (a crash, a sanitizer report, another
// exception type escaping) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_files.hpp"
#include "scene/load/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        clpath::fuzz::check_scene(clpath::parse_scene_file(text, "fuzz/scene.json", clpath::fuzz::options()));
    } catch (const clpath::Error&) {
    }
    return 0;
}
