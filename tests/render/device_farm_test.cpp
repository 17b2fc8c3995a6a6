// Rendering over several devices: the image is the same bits whichever device
// rendered which chunk, and time-budgeted renders (whose sample counts depend
// on timing) agree in distribution. CTest runs this with PoCL showing two CPU
// devices (POCL_DEVICES="pthread pthread", tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include "cl/device.hpp"
#include "render/device_farm.hpp"
#include "scene/builtin_scenes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"

using namespace clpath;

namespace {

Scene small_cornell() { return test::small_cornell(32, 24); }

std::vector<DeviceInfo> devices(std::size_t n) {
    std::vector<DeviceInfo> all = list_devices();
    if (all.size() < n)
        throw std::runtime_error("this test needs " + std::to_string(n) +
                                 " OpenCL devices; run it through CTest, which asks PoCL for two");
    all.resize(n);
    return all;
}

ExactFilm render(const Scene& scene, const RenderSettings& st, std::size_t device_count, ChunkPlan plan,
                 double seconds, std::vector<DeviceShare>* shares = nullptr) {
    DeviceFarm farm(devices(device_count), scene, st);
    ChunkQueue queue(plan, seconds);
    farm.start(queue);
    farm.wait();
    if (shares) *shares = farm.shares();
    return farm.snapshot();
}

}  // namespace

TEST(DeviceFarm, TwoDevicesGiveTheSameBitsAsOne) {
    const Scene scene = small_cornell();
    RenderSettings st;
    st.seed = 11;
    const ChunkPlan plan{24, 2};
    const ExactFilm one = render(scene, st, 1, plan, 0);
    std::vector<DeviceShare> shares;
    const ExactFilm two = render(scene, st, 2, plan, 0, &shares);
    EXPECT_EQ(one.samples_per_pixel(), 24u);
    EXPECT_EQ(two.samples_per_pixel(), 24u);
    EXPECT_EQ(one.sums(), two.sums());
    EXPECT_EQ(one.mean().rgb, two.mean().rgb);
    ASSERT_EQ(shares.size(), 2u);
    EXPECT_EQ(shares[0].samples_per_pixel + shares[1].samples_per_pixel, 24u);
    EXPECT_EQ(shares[0].chunks + shares[1].chunks, 12u);

    // Control: another seed is another image, so equality above is not vacuous.
    st.seed = 12;
    EXPECT_NE(render(scene, st, 1, plan, 0).sums(), one.sums());
}

TEST(DeviceFarm, TimeBudgetedRendersAgreeInDistribution) {
    // K runs per side with independent seeds: one device against two, each for
    // a time budget, so their sample counts differ run to run. Blocks of 8x8
    // pixels are z-tested at a Sidak-corrected level of 1e-7 over all blocks:
    // a false failure is rarer than once in ten million runs.
    const Scene scene = small_cornell();
    constexpr int kRuns = 4;
    std::vector<Image> one, two;
    RenderSettings st;
    for (int k = 0; k < kRuns; ++k) {
        st.seed = 100 + k;
        one.push_back(render(scene, st, 1, {0, 1}, 0.4).mean());
        st.seed = 200 + k;
        two.push_back(render(scene, st, 2, {0, 1}, 0.4).mean());
        ASSERT_GT(one.back().rgb.size(), 0u);
    }
    const test::Agreement agree = test::image_agreement(one, two, 8, 1e-7);
    EXPECT_TRUE(agree.ok()) << agree.describe();

    // Control: the same runs, 25 % too bright on one side, are rejected.
    std::vector<Image> bright = two;
    for (auto& img : bright)
        for (auto& v : img.rgb) v *= 1.25f;
    EXPECT_FALSE(test::image_agreement(one, bright, 8, 1e-7).ok());
}
