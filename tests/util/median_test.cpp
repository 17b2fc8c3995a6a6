// median_of (host/util/median.hpp): what bench scaling reports for its ray
// batches' launches and its path passes.
#include <gtest/gtest.h>

#include "util/median.hpp"

namespace clpath {
namespace {

TEST(Median, OddCountIsTheMiddleValue) { EXPECT_EQ(median_of({3.0, 1.0, 2.0}), 2.0); }

TEST(Median, EvenCountIsTheMeanOfTheMiddleTwo) { EXPECT_EQ(median_of({4.0, 1.0, 3.0, 2.0}), 2.5); }

TEST(Median, NoValuesGiveZero) { EXPECT_EQ(median_of({}), 0.0); }

// Why the scaling table takes it: one launch slowed to 1.6x (another process
// on a core) leaves the median of three where it was, while the mean moves
// by a fifth. The control is the mean itself.
TEST(Median, OneSlowLaunchOfThreeDoesNotMoveIt) {
    const std::vector<double> launches{100.0, 160.0, 101.0};
    EXPECT_EQ(median_of(launches), 101.0);
    const double mean = (launches[0] + launches[1] + launches[2]) / 3;
    EXPECT_GT(mean / median_of(launches), 1.19);
}

}  // namespace
}  // namespace clpath
