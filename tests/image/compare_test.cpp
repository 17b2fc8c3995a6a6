// Image comparison against values worked out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "image/compare.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {
Image constant(int w, int h, float v) {
    Image im;
    im.width = w;
    im.height = h;
    im.rgb.assign(std::size_t(w) * h * 3, v);
    return im;
}
}  // namespace

TEST(Compare, KnownDifference) {
    Image a = constant(4, 2, 0.5f), b = constant(4, 2, 0.25f);
    a.rgb[(1 * 4 + 3) * 3 + 1] = 1.25f;  // one channel of pixel (3,1) differs by 1.0
    const ImageComparison c = compare_images(a, b);
    const double mse = (23 * 0.0625 + 1.0) / 24;
    EXPECT_DOUBLE_EQ(c.mse, mse);
    EXPECT_DOUBLE_EQ(c.rmse, std::sqrt(mse));
    EXPECT_NEAR(c.psnr, -10 * std::log10(mse), 1e-12);
    EXPECT_NEAR(c.relmse, (23 * 0.0625 / (0.0625 + 0.01) + 1.0 / (0.0625 + 0.01)) / 24, 1e-12);
    EXPECT_FLOAT_EQ(c.max_abs_diff, 1.0f);
    EXPECT_EQ(c.max_x, 3);
    EXPECT_EQ(c.max_y, 1);
    EXPECT_NEAR(c.mean_a[1], (7 * 0.5 + 1.25) / 8, 1e-12);
    EXPECT_NEAR(c.mean_b[0], 0.25, 1e-12);
}

TEST(Compare, IdenticalIsInfinitePsnr) {
    const Image a = constant(3, 3, 0.7f);
    const ImageComparison c = compare_images(a, a);
    EXPECT_EQ(c.mse, 0.0);
    EXPECT_TRUE(std::isinf(c.psnr));
}

TEST(Compare, ClampAndMask) {
    Image a = constant(2, 1, 0.5f), b = constant(2, 1, 0.5f);
    for (int ch = 0; ch < 3; ++ch) {
        a.rgb[3 + ch] = 20.0f;  // a bright emitter pixel in both, differing
        b.rgb[3 + ch] = 10.0f;
    }
    EXPECT_GT(compare_images(a, b).mse, 1.0);
    CompareOptions clamp;
    clamp.clamp = 1.0f;
    EXPECT_EQ(compare_images(a, b, clamp).mse, 0.0);
    CompareOptions mask;
    mask.mask_above = 5.0f;
    const ImageComparison m = compare_images(a, b, mask);
    EXPECT_EQ(m.pixels, 1u);
    EXPECT_EQ(m.mse, 0.0);
}

TEST(Compare, SizeMismatchIsAnError) {
    EXPECT_THROW(compare_images(constant(2, 2, 0), constant(2, 3, 0)), Error);
}

TEST(Compare, NanDifferenceIsReportedAsLargest) {
    Image a = constant(2, 2, 0.5f);
    const Image b = constant(2, 2, 0.5f);
    a.rgb[4] = std::nanf("");
    const ImageComparison c = compare_images(a, b);
    EXPECT_TRUE(std::isnan(c.max_abs_diff));
    EXPECT_EQ(c.max_x, 1);
}

// The grown mask covers the emitter's neighbours (partly covered edge pixels)
// and nothing farther away.
TEST(Compare, MaskGrowsAroundMaskedPixels) {
    Image a = constant(5, 1, 0.5f), b = constant(5, 1, 0.5f);
    b.rgb[2 * 3] = 10.0f;  // pixel 2: an emitter in the reference
    a.rgb[1 * 3] = 0.9f;   // pixel 1: its noisy neighbour
    a.rgb[4 * 3] = 0.7f;   // pixel 4: two away
    CompareOptions o;
    o.mask_above = 5.0f;
    o.mask_grow = 1;
    const ImageComparison c = compare_images(a, b, o);
    EXPECT_EQ(c.pixels, 2u);  // pixels 0 and 4
    EXPECT_NEAR(c.mse, 0.2 * 0.2 / 6, 1e-7);
}
