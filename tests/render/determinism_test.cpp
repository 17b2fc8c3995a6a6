// The same seed on the same device gives the identical image, however the
// samples are split into launches; another seed gives other noise.
#include <gtest/gtest.h>

#include "scene/builtin_scenes.hpp"
#include "support/render_helpers.hpp"

using namespace clpath;

namespace {
Scene small_cornell() { return test::small_cornell(40, 32); }
}  // namespace

TEST(Determinism, SameSeedSameImage) {
    RenderSettings st;
    st.seed = 3;
    const auto a = test::render(small_cornell(), st, 4);
    const auto b = test::render(small_cornell(), st, 4);
    EXPECT_EQ(a.linear.rgb, b.linear.rgb);
    EXPECT_EQ(a.srgb8, b.srgb8);
}

TEST(Determinism, LaunchSplitDoesNotMatter) {
    RenderSettings st;
    st.seed = 3;
    const auto whole = test::render(small_cornell(), st, 6);
    Renderer r(test::device(), small_cornell(), st);
    for (int i = 0; i < 3; ++i) r.add_samples(2);
    EXPECT_EQ(r.resolve().linear.rgb, whole.linear.rgb);
}

TEST(Determinism, OtherSeedOtherNoise) {
    RenderSettings st;
    st.seed = 3;
    const auto a = test::render(small_cornell(), st, 4);
    st.seed = 4;
    const auto b = test::render(small_cornell(), st, 4);
    // Values that are zero in both (no path found light) or that see only the
    // lamp (constant radiance) agree whatever the seed; noisy ones must not.
    std::size_t differ = 0, lit = 0;
    for (std::size_t i = 0; i < a.linear.rgb.size(); ++i) {
        if (a.linear.rgb[i] == 0 && b.linear.rgb[i] == 0) continue;
        ++lit;
        differ += a.linear.rgb[i] != b.linear.rgb[i];
    }
    EXPECT_GT(differ, lit * 8 / 10) << "of " << lit << " lit values";
}
