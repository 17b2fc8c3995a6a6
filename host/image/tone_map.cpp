#include "image/tone_map.hpp"

#include <algorithm>
#include <cmath>

#include "util/error.hpp"

namespace clpath {
namespace {

// IEC 61966-2-1, as kernels/film.cl encodes the film's own sRGB image.
float srgb_encode(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

// K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2015): a rational fit of the
// ACES reference rendering transform, per channel. His 0.6 pre-scale maps the
// curve's mid-grey to where an untone-mapped image has it.
float aces_fitted(float x) {
    x *= 0.6f;
    const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
    return (x * (a * x + b)) / (x * (c * x + d) + e);
}

}  // namespace

std::vector<std::string> tone_map_names() { return {"clamp", "reinhard", "aces"}; }

ToneMap parse_tone_map(const std::string& name) {
    if (name == "clamp") return ToneMap::Clamp;
    if (name == "reinhard") return ToneMap::Reinhard;
    if (name == "aces") return ToneMap::Aces;
    throw UsageError("--tonemap '" + name + "': unknown tone map (choose one of: clamp, reinhard, aces)");
}

void tone_map_pixel(const float in[3], const DisplaySettings& d, float out[3]) {
    const float scale = std::exp2(d.exposure_stops);
    float c[3];
    for (int i = 0; i < 3; ++i) c[i] = std::isfinite(in[i]) ? std::max(in[i], 0.0f) * scale : 0.0f;
    switch (d.tone_map) {
    case ToneMap::Clamp:
        break;
    case ToneMap::Reinhard: {
        // Reinhard, Stark, Shirley and Ferwerda, "Photographic Tone Reproduction
        // for Digital Images" (SIGGRAPH 2002), eq. 3 on Rec. 709 luminance: the
        // colour is scaled as a whole, so hues do not shift.
        const float lum = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
        const float k = lum > 0 ? 1.0f / (1.0f + lum) : 1.0f;
        for (float& v : c) v *= k;
        break;
    }
    case ToneMap::Aces:
        for (float& v : c) v = aces_fitted(v);
        break;
    }
    for (int i = 0; i < 3; ++i) out[i] = std::clamp(c[i], 0.0f, 1.0f);
}

std::vector<std::uint8_t> display_srgb8(const Image& linear, const DisplaySettings& d) {
    const std::size_t n = std::size_t(linear.width) * std::size_t(linear.height);
    std::vector<std::uint8_t> out(n * 4);
    for (std::size_t p = 0; p < n; ++p) {
        float c[3];
        tone_map_pixel(&linear.rgb[p * 3], d, c);
        for (int i = 0; i < 3; ++i) out[p * 4 + i] = std::uint8_t(srgb_encode(c[i]) * 255.0f + 0.5f);
        out[p * 4 + 3] = 255;
    }
    return out;
}

}  // namespace clpath
