// The SAH builder's binning (host/bvh/binning.cpp): the AVX path and the
// portable one fill the same bins bit for bit (so a tree does not depend on
// the CPU it was built on), and a small node's packed bins (bin_refs_sparse)
// are the full binning's occupied bins, in order.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "bvh/binning.hpp"

using namespace clpath::bvh_build;

namespace {

// Triangle boxes over [-1, 1]^3, a few flat (lo = hi on an axis) and some
// touching zero from either side, so signed zeros meet in min and max.
std::vector<Ref> random_refs(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.0f, 0.05f);
    std::vector<Ref> refs(n);
    for (std::size_t i = 0; i < n; ++i) {
        Ref& r = refs[i];
        for (int a = 0; a < 3; ++a) {
            const float c = u(rng);
            r.lo[a] = c - s(rng);
            r.hi[a] = int(i % 7) == a ? r.lo[a] : c + s(rng);
            if (i % 11 == 0) r.lo[a] = (i / 11) % 2 ? -0.0f : 0.0f;
            if (i % 13 == 0) r.hi[a] = (i / 13) % 2 ? 0.0f : -0.0f;
            if (r.hi[a] < r.lo[a]) r.hi[a] = r.lo[a];
        }
        r.prim = std::uint32_t(i);
        r.pad = 0;
    }
    return refs;
}

Box4 centroid_bounds(const std::vector<Ref>& refs, std::size_t begin, std::size_t end) {
    Box4 c;
    for (std::size_t i = begin; i < end; ++i) c.grow_point(centroid(load3(refs[i].lo), load3(refs[i].hi)));
    return c;
}

// bitwise: signed zeros must match too; else equal values (-0 == +0): the
// dense and sparse binnings meet a bin's triangles in different orders.
void expect_same_box(const Box4& a, const Box4& b, bool bitwise) {
    alignas(16) float x[8], y[8];
    store4(x, a.lo);
    store4(x + 4, a.hi);
    store4(y, b.lo);
    store4(y + 4, b.hi);
    for (int i : {0, 1, 2, 4, 5, 6}) {
        if (bitwise)
            EXPECT_EQ(std::memcmp(&x[i], &y[i], 4), 0) << "lane " << i << ": " << x[i] << " vs " << y[i];
        else
            EXPECT_EQ(x[i], y[i]) << "lane " << i;
    }
}

}  // namespace

TEST(Binning, AvxAndPortableAgreeBitForBit) {
    if (!avx_available()) GTEST_SKIP() << "no AVX on this CPU";
    const std::vector<Ref> refs = random_refs(5000, 3);
    for (int bins : {2, 16, 64, 256})
        for (std::size_t n : {std::size_t(bins), std::size_t(bins) + 1, std::size_t(127), std::size_t(128), std::size_t(131), std::size_t(1000), refs.size()}) {
            const BinMap map(centroid_bounds(refs, 0, n), bins);
            auto a = std::make_unique<Bins>(), b = std::make_unique<Bins>();
            bin_refs_portable(refs.data(), 0, std::uint32_t(n), map, *a);
            bin_refs_avx(refs.data(), 0, std::uint32_t(n), map, *b);
            std::uint32_t total = 0;
            for (int ax = 0; ax < 3; ++ax)
                for (int k = 0; k < bins; ++k) {
                    EXPECT_EQ(a->count[ax][k], b->count[ax][k]);
                    if (a->count[ax][k]) expect_same_box(a->box[ax][k], b->box[ax][k], true);
                    total += a->count[ax][k];
                }
            EXPECT_EQ(total, 3 * n);
        }
}

TEST(Binning, PairBinsAreTheSparseBins) {
    const std::vector<Ref> refs = random_refs(400, 9);
    for (int bins : {2, 16, 200})
        for (std::uint32_t b0 = 0; b0 + 1 < refs.size(); b0 += 2) {
            const BinMap map(centroid_bounds(refs, b0, b0 + 2), bins);
            auto pair = std::make_unique<Bins>(), sparse = std::make_unique<Bins>();
            BinList lp[3], ls[3];
            bin_refs_pair(refs.data(), b0, map, *pair, lp);
            bin_refs_sparse(refs.data(), b0, b0 + 2, map, *sparse, ls);
            for (int ax = 0; ax < 3; ++ax) {
                ASSERT_EQ(lp[ax].size, ls[ax].size);
                for (int j = 0; j < ls[ax].size; ++j) {
                    EXPECT_EQ(lp[ax].bin[j], ls[ax].bin[j]);
                    EXPECT_EQ(pair->count[ax][j], sparse->count[ax][j]);
                    expect_same_box(pair->box[ax][j], sparse->box[ax][j], true);
                }
            }
        }
}

TEST(Binning, SparseBinsAreTheOccupiedBinsInOrder) {
    const std::vector<Ref> refs = random_refs(300, 5);
    for (int bins : {8, 16, 200}) {
        std::size_t begin = 0;
        for (std::size_t n = 1; n < std::size_t(bins) && begin + n <= refs.size(); begin += n, n += 3) {
            const std::uint32_t b0 = std::uint32_t(begin), e0 = std::uint32_t(begin + n);
            const BinMap map(centroid_bounds(refs, begin, begin + n), bins);
            auto dense = std::make_unique<Bins>(), sparse = std::make_unique<Bins>();
            bin_refs(refs.data(), b0, e0, map, *dense);
            BinList lists[3];
            bin_refs_sparse(refs.data(), b0, e0, map, *sparse, lists);
            for (int ax = 0; ax < 3; ++ax) {
                int j = 0;
                for (int k = 0; k < bins; ++k) {
                    if (!dense->count[ax][k]) continue;
                    ASSERT_LT(j, lists[ax].size);
                    EXPECT_EQ(lists[ax].bin[j], k);
                    EXPECT_EQ(sparse->count[ax][j], dense->count[ax][k]);
                    expect_same_box(sparse->box[ax][j], dense->box[ax][k], false);
                    ++j;
                }
                EXPECT_EQ(j, lists[ax].size) << "bins " << bins << ", n " << n;
            }
        }
    }
}
