#pragma once
// Images in and out. PNG (8-bit sRGB) and EXR (linear float) go through
// OpenImageIO; PFM (linear float) is written and read here, so a build without
// OpenImageIO (-DCLPATH_WITH_OIIO=OFF) still saves exact images.
#include <cstdint>
#include <string>
#include <vector>

namespace clpath {

// A linear RGB float image, row 0 at the top.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 floats per pixel
    float at(int x, int y, int c) const { return rgb[(std::size_t(y) * width + x) * 3 + c]; }
};

// What a render produces: the linear mean and its 8-bit sRGB encoding (both
// made by the film kernel, so display conversion has one definition).
struct RenderedImage {
    Image linear;
    std::vector<std::uint8_t> srgb8;  // 4 bytes per pixel, RGBA
};

// Fails early, before any rendering, with a message naming the path, if the
// format is unknown, not available in this build, or the folder is missing
// or not writable.
void check_output_path(const std::string& path);

// Writes through a temporary file and a rename: no half-written image is left
// behind on failure.
void write_image(const std::string& path, const RenderedImage& image);

// Reads EXR, PFM (and with OpenImageIO any format it knows; 8-bit files are
// decoded from sRGB to linear).
Image read_image(const std::string& path);

// Reads only the file's header, as read_image would: throws clpath::Error
// naming the path if it is not an image this build reads, or has fewer than
// three channels. For options that name an image, checked before rendering.
void check_image_readable(const std::string& path);

void write_pfm(const std::string& path, const Image& image);
Image read_pfm(const std::string& path);

}  // namespace clpath
