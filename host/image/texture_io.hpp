#pragma once
// Texture images for materials, decoded through OpenImageIO from a file or
// from bytes in memory (a glTF buffer view or data URI). 8-bit and 16-bit
// files become RGBA8 as stored (colour-space decoding is the renderer's, per
// use); half and float files (EXR, HDR) become linear RGBA floats.
#include <cstdint>
#include <string>
#include <vector>

namespace clpath {

struct TextureImage {
    int width = 0, height = 0;
    bool is_float = false;
    std::vector<std::uint8_t> rgba8;  // 4 per texel, row 0 at the top; alpha 255 where the file has none
    std::vector<float> rgba32;        // 4 per texel, when is_float; alpha 1 where the file has none
};

// Largest side accepted: a bound on memory for a hostile file.
constexpr int kMaxTextureSide = 16384;

// `name` gives the format (by its extension, e.g. "x.png") and is the start
// of every message. Throws clpath::Error "NAME: cannot decode the image: ...".
TextureImage decode_texture(const std::string& bytes, const std::string& name);

}  // namespace clpath
