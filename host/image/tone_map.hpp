#pragma once
// From linear radiance to an 8-bit sRGB picture for PNG output: an exposure
// in stops, then a tone-mapping curve, then the sRGB transfer function.
// Float outputs (EXR, PFM) are written linear and never pass through here.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace clpath {

enum class ToneMap {
    Clamp,     // values above 1 clip to white (what the film kernel's sRGB image does)
    Reinhard,  // L / (1 + L) on luminance, hue kept
    Aces,      // Narkowicz's fit of the ACES filmic curve
};

std::vector<std::string> tone_map_names();      // "clamp", "reinhard", "aces"
ToneMap parse_tone_map(const std::string& name);  // throws clpath::UsageError naming the choices

struct DisplaySettings {
    float exposure_stops = 0;  // radiance times 2^stops
    ToneMap tone_map = ToneMap::Clamp;
    bool is_identity() const { return exposure_stops == 0 && tone_map == ToneMap::Clamp; }
};

// One display-referred value in [0, 1] per channel, before sRGB encoding.
void tone_map_pixel(const float in[3], const DisplaySettings& d, float out[3]);

// RGBA, 4 bytes per pixel, alpha 255, row 0 at the top like the input.
std::vector<std::uint8_t> display_srgb8(const Image& linear, const DisplaySettings& d);

}  // namespace clpath
