// The SAH sweeps (host/bvh/sah_sweep.cpp): sah_sweep_all_bins, the three
// axes interleaved, makes sah_sweep's choice axis by axis bit for bit (the
// cost, the axis, the bin), whichever axes are swept, ties included: the
// first of equal costs wins, in axis order, then bin order.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "bvh/binning.hpp"
#include "bvh/sah_sweep.hpp"

using namespace clpath::bvh_build;

namespace {

struct Choice {
    float cost = std::numeric_limits<float>::infinity();
    int axis = -1, bin = 0;
};

Choice per_axis(const Bins& bins, int nbins, const bool sweep[3], std::uint32_t n, const int order[3]) {
    BinList all;
    list_all(nbins, all);
    Choice c;
    for (int i = 0; i < 3; ++i)
        if (sweep[order[i]]) sah_sweep(bins, order[i], all, n, c.cost, c.axis, c.bin);
    return c;
}

Choice interleaved(const Bins& bins, int nbins, const bool sweep[3], std::uint32_t n) {
    Choice c;
    sah_sweep_all_bins(bins, nbins, sweep, n, c.cost, c.axis, c.bin);
    return c;
}

void expect_same(const Choice& a, const Choice& b, const std::string& what) {
    EXPECT_EQ(a.axis, b.axis) << what;
    EXPECT_EQ(a.bin, b.bin) << what;
    EXPECT_EQ(std::memcmp(&a.cost, &b.cost, sizeof(float)), 0) << what << ": " << a.cost << " vs " << b.cost;
}

// Bins filled by binning n random triangle boxes (some bins empty when n is small).
Bins random_bins(int nbins, std::size_t n, std::uint32_t seed, std::uint32_t& count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.0f, 0.1f);
    std::vector<Ref> refs(n);
    Box4 cbox;
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < 3; ++a) {
            const float c = u(rng) * (a == 2 ? 0.1f : 1.0f);
            refs[i].lo[a] = c - s(rng);
            refs[i].hi[a] = c + s(rng);
        }
        refs[i].prim = std::uint32_t(i);
        refs[i].pad = 0;
        cbox.grow_point(centroid(load3(refs[i].lo), load3(refs[i].hi)));
    }
    Bins bins;
    bin_refs(refs.data(), 0, std::uint32_t(n), BinMap(cbox, nbins), bins);
    count = std::uint32_t(n);
    return bins;
}

const int kAxisOrder[3] = {0, 1, 2};

}  // namespace

TEST(SahSweep, AllBinsInterleavedChoosesAsAxisByAxis) {
    std::uint32_t seed = 1;
    for (int nbins : {2, 8, 16, 64, 256})
        for (std::size_t n : {std::size_t(2), std::size_t(nbins), std::size_t(3 * nbins + 1), std::size_t(4000)})
            for (int mask = 1; mask < 8; ++mask) {
                std::uint32_t count = 0;
                const Bins bins = random_bins(nbins, n, seed++, count);
                const bool sweep[3] = {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0};
                expect_same(per_axis(bins, nbins, sweep, count, kAxisOrder), interleaved(bins, nbins, sweep, count),
                            "bins " + std::to_string(nbins) + ", n " + std::to_string(n) + ", axes " +
                                std::to_string(mask));
            }
}

// The same bins on all three axes: every axis prices every boundary the
// same, so the first swept axis must win; and where two boundaries of an
// axis split alike (empty bins between them), the first boundary.
TEST(SahSweep, TiesGoToTheFirstAxisAndBoundary) {
    constexpr int nbins = 4;
    Bins bins, gap;
    bins.clear(nbins);
    gap.clear(nbins);
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < nbins; ++k) {
            // Unit cubes at 0, 1, 2, 3 along x, one triangle each: the
            // boundary after bin 1 is the cheapest (10 x 2 + 10 x 2 = 40,
            // against 6 x 1 + 14 x 3 = 48 after bin 0 or 2).
            bins.box[a][k].grow(set4(float(k), 0, 0, 0), set4(float(k) + 1, 1, 1, 0));
            bins.count[a][k] = 1;
            if (k == 0 || k == 3) {  // bins 1 and 2 empty: the boundaries after 0, 1 and 2 split alike
                gap.box[a][k] = bins.box[a][k];
                gap.count[a][k] = 1;
            }
        }
    for (int first = 0; first < 3; ++first) {
        bool sweep[3] = {false, false, false};
        for (int a = first; a < 3; ++a) sweep[a] = true;
        const Choice c = interleaved(bins, nbins, sweep, 4);
        EXPECT_EQ(c.axis, first);
        EXPECT_EQ(c.bin, 1);
        expect_same(per_axis(bins, nbins, sweep, 4, kAxisOrder), c, "first axis " + std::to_string(first));
        const Choice g = interleaved(gap, nbins, sweep, 2);
        EXPECT_EQ(g.axis, first);
        EXPECT_EQ(g.bin, 0);
        expect_same(per_axis(gap, nbins, sweep, 2, kAxisOrder), g, "gap, first axis " + std::to_string(first));
    }
    // Control: the comparisons above can tell the axis order apart. Swept
    // last axis first, the reference picks axis 2, which the interleaved
    // sweep does not.
    const bool all[3] = {true, true, true};
    const int reversed[3] = {2, 1, 0};
    EXPECT_EQ(per_axis(bins, nbins, all, 4, reversed).axis, 2);
    EXPECT_NE(per_axis(bins, nbins, all, 4, reversed).axis, interleaved(bins, nbins, all, 4).axis);
}

// Equal costs on two axes at different boundaries: axis order decides, not
// boundary order (axis 0's best boundary is its last, axis 1's its first).
TEST(SahSweep, EqualCostsOnTwoAxesGoToTheFirstAxis) {
    constexpr int nbins = 4;
    Bins bins;
    bins.clear(nbins);
    const std::uint32_t counts[4] = {1, 1, 1, 5};
    for (int k = 0; k < nbins; ++k) {
        // Axis 0: unit cubes at 0..3 along x, five triangles in the last:
        // cheapest after bin 2 (14 x 3 + 6 x 5 = 72). Axis 1: the mirror
        // image, cheapest after bin 0, at the same cost. Axis 2: one bin.
        bins.box[0][k].grow(set4(float(k), 0, 0, 0), set4(float(k) + 1, 1, 1, 0));
        bins.count[0][k] = counts[k];
        bins.box[1][nbins - 1 - k] = bins.box[0][k];
        bins.count[1][nbins - 1 - k] = counts[k];
    }
    bins.box[2][0].grow(set4(0, 0, 0, 0), set4(4, 1, 1, 0));
    bins.count[2][0] = 8;
    const bool all[3] = {true, true, true};
    const Choice c = interleaved(bins, nbins, all, 8);
    EXPECT_EQ(c.axis, 0);
    EXPECT_EQ(c.bin, 2);
    EXPECT_EQ(c.cost, 72.0f);
    expect_same(per_axis(bins, nbins, all, 8, kAxisOrder), c, "two axes tied");
}

// All triangles in one bin: no boundary splits them, whether the bin is
// the first (every boundary has them all on the left) or the last.
TEST(SahSweep, OneOccupiedBinIsNoSplit) {
    constexpr int nbins = 16;
    for (int occupied : {0, nbins - 1}) {
        Bins bins;
        bins.clear(nbins);
        for (int a = 0; a < 3; ++a) {
            bins.box[a][occupied].grow(set4(0, 0, 0, 0), set4(1, 1, 1, 0));
            bins.count[a][occupied] = 5;
        }
        const bool all[3] = {true, true, true};
        const Choice c = interleaved(bins, nbins, all, 5);
        EXPECT_EQ(c.axis, -1) << "bin " << occupied;
        expect_same(per_axis(bins, nbins, all, 5, kAxisOrder), c, "bin " + std::to_string(occupied));
    }
}
