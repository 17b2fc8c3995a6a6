// Exposure and tone mapping of PNG output (image/tone_map.hpp).
#include <cmath>

#include <gtest/gtest.h>

#include "image/tone_map.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

float mapped(float v, ToneMap t, float stops = 0) {
    const float in[3] = {v, v, v};
    float out[3];
    DisplaySettings d;
    d.tone_map = t;
    d.exposure_stops = stops;
    tone_map_pixel(in, d, out);
    return out[0];
}

TEST(ToneMap, ClampIsTheIdentityBelowWhite) {
    EXPECT_FLOAT_EQ(mapped(0.25f, ToneMap::Clamp), 0.25f);
    EXPECT_FLOAT_EQ(mapped(4.0f, ToneMap::Clamp), 1.0f);
    EXPECT_FLOAT_EQ(mapped(0.25f, ToneMap::Clamp, 1), 0.5f);   // one stop doubles
    EXPECT_FLOAT_EQ(mapped(0.25f, ToneMap::Clamp, -2), 0.0625f);
}

TEST(ToneMap, ReinhardCompressesOnLuminance) {
    // Grey: L / (1 + L) exactly.
    EXPECT_NEAR(mapped(1.0f, ToneMap::Reinhard), 0.5f, 1e-6f);
    EXPECT_NEAR(mapped(3.0f, ToneMap::Reinhard), 0.75f, 1e-6f);
    // Colour keeps its hue: both channels scaled by the same factor.
    const float in[3] = {0.4f, 0.2f, 0.0f};
    float out[3];
    DisplaySettings d;
    d.tone_map = ToneMap::Reinhard;
    tone_map_pixel(in, d, out);
    EXPECT_NEAR(out[0] / out[1], 2.0f, 1e-5f);
}

TEST(ToneMap, AcesFitMatchesNarkowicz) {
    // f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14) at x = 0.6 * input.
    auto f = [](double x) { x *= 0.6; return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); };
    for (float v : {0.05f, 0.18f, 1.0f, 4.0f})
        EXPECT_NEAR(mapped(v, ToneMap::Aces), std::min(1.0, f(v)), 1e-6) << v;
    EXPECT_EQ(mapped(0, ToneMap::Aces), 0.0f);
    EXPECT_EQ(mapped(1e6f, ToneMap::Aces), 1.0f);  // saturates, never above white
    EXPECT_LT(mapped(1.0f, ToneMap::Aces), mapped(2.0f, ToneMap::Aces));
}

TEST(ToneMap, NonFiniteAndNegativeBecomeBlack) {
    EXPECT_EQ(mapped(NAN, ToneMap::Aces), 0.0f);
    EXPECT_EQ(mapped(-1.0f, ToneMap::Reinhard), 0.0f);
}

TEST(ToneMap, EncodesSrgbBytes) {
    Image img;
    img.width = 2;
    img.height = 1;
    img.rgb = {0, 0, 0, 1, 1, 1};
    DisplaySettings d;
    const auto px = display_srgb8(img, d);
    ASSERT_EQ(px.size(), 8u);
    EXPECT_EQ(px[0], 0);
    EXPECT_EQ(px[4], 255);
    EXPECT_EQ(px[7], 255);
    d.tone_map = ToneMap::Reinhard;  // white 1 becomes 0.5: sRGB 188
    EXPECT_EQ(display_srgb8(img, d)[4], 188);
}

TEST(ToneMap, UnknownNameListsTheChoices) {
    EXPECT_THROW(parse_tone_map("filmic"), UsageError);
    EXPECT_EQ(parse_tone_map("aces"), ToneMap::Aces);
}

}  // namespace
}  // namespace clpath
