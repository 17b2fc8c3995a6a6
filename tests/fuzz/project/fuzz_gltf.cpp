// libFuzzer target: the glTF loader (tinygltf plus clpath's checks of every
// accessor, index, node, material, texture, camera and light), through the
// bare-glTF scene. An input is a .gltf (JSON) or .glb (binary) file; it may
// name fuzz/model.bin and fuzz/texture.rgba, and textures decode through a
// stand-in for OpenImageIO ("RGBA", width, height, texels), so the fuzzer
// explores the loader rather than an image library.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_files.hpp"
#include "scene/load/gltf_scene.hpp"

namespace {
clpath::TextureImage decode(const std::string& bytes, const std::string& name) {
    if (bytes.size() < 6 || bytes.compare(0, 4, "RGBA") != 0) throw clpath::Error(name + ": cannot decode the image");
    clpath::TextureImage t;
    t.width = static_cast<unsigned char>(bytes[4]);
    t.height = static_cast<unsigned char>(bytes[5]);
    t.rgba8.assign(bytes.begin() + 6, bytes.end());
    if (t.width == 0 || t.height == 0 || t.rgba8.size() != std::size_t(t.width) * t.height * 4)
        throw clpath::Error(name + ": cannot decode the image: wrong size");
    return t;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    clpath::LoadOptions o = clpath::fuzz::options();
    const auto files = o.read_file;
    o.read_file = [&](const std::string& path) { return path == "fuzz/model.gltf" ? input : files(path); };
    const auto exists = o.file_exists;
    o.file_exists = [&](const std::string& path) { return path == "fuzz/model.gltf" || exists(path); };
    o.decode_texture = decode;
    o.gltf_camera = size % 2 ? "1" : "";
    try {
        clpath::fuzz::check_scene(clpath::gltf_scene("fuzz/model.gltf", o));
    } catch (const clpath::Error&) {
    }
    return 0;
}
