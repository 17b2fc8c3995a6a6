// Small nodes split without bins (host/bvh/small_node.cpp): the decision,
// the partition and the children's boxes must be the binned path's bit for
// bit (bin_refs_sparse, sah_sweep, partition_refs, the bins' union), or the
// tree would depend on which path a node took.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "bvh/binning.hpp"
#include "bvh/partition.hpp"
#include "bvh/sah_sweep.hpp"
#include "bvh/small_node.hpp"
#include "support/box_bits.hpp"

using namespace clpath::bvh_build;

namespace {

// A few records on a coarse grid (so centroids share bins and coordinates),
// some flat, some bounds at +0 or -0 (so the order of a union shows in a
// zero's sign), some records repeated. overlap: each box also spans most of
// the grid, so that no split pays and small nodes stay leaves.
std::vector<Ref> records(int n, bool overlap, std::mt19937& rng) {
    std::uniform_int_distribution<int> grid(-4, 4), coin(0, 5);
    std::vector<Ref> r(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        Ref& x = r[std::size_t(i)];
        if (i > 0 && coin(rng) == 0) {
            x = r[std::size_t(i - 1)];
        } else {
            for (int a = 0; a < 3; ++a) {
                const float c = 0.25f * float(grid(rng));
                x.lo[a] = coin(rng) == 0 ? (coin(rng) % 2 ? -0.0f : 0.0f) : c;
                x.hi[a] = coin(rng) == 0 ? x.lo[a] : std::max(x.lo[a], c + 0.125f * float(coin(rng)));
            }
        }
        if (overlap)
            for (int a = 0; a < 3; ++a) {
                x.lo[a] = std::min(x.lo[a], -0.75f);
                x.hi[a] = std::max(x.hi[a], 0.75f);
            }
        x.prim = std::uint32_t(i);
        x.pad = 0;
    }
    return r;
}

// The binned path, as binned_builder.cpp's decide() and subtree() take it.
SmallSplit binned(const std::vector<Ref>& src, std::vector<Ref>& dst, const Box4& box, const Box4& cbox, int bins,
                  int max_leaf, float traversal_cost) {
    SmallSplit out;
    const std::uint32_t n = std::uint32_t(src.size());
    const F4 e = cbox.hi - cbox.lo;
    const float ext[3] = {lane(e, 0), lane(e, 1), lane(e, 2)};
    const int axis_long = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : (ext[1] >= ext[2] ? 1 : 2);
    if (!(ext[axis_long] > 0)) return out;
    const BinMap map(cbox, bins);
    auto b = std::make_unique<Bins>();
    BinList lists[3];
    if (n < std::uint32_t(bins)) {
        bin_refs_sparse(src.data(), 0, n, map, *b, lists);
    } else {
        bin_refs(src.data(), 0, n, map, *b);
        for (int a = 0; a < 3; ++a) list_all(bins, lists[a]);
    }
    float best_cost = std::numeric_limits<float>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a)
        if (ext[a] > 0) sah_sweep(*b, a, lists[a], n, best_cost, best_axis, best_bin);
    const float node_area = area(box);
    const float split_cost = traversal_cost + (node_area > 0 ? best_cost / node_area : 0.0f);
    if (n <= std::uint32_t(max_leaf) && (best_axis < 0 || float(n) <= split_cost)) {
        out.kind = SmallSplit::Leaf;
        return out;
    }
    if (best_axis < 0) return out;
    out.kind = SmallSplit::Split;
    out.mid = partition_refs(src.data(), dst.data(), 0, n, map, best_axis, best_bin, out.left_cbox, out.right_cbox);
    for (int j = 0; j < lists[best_axis].size; ++j)
        (lists[best_axis].bin[j] <= best_bin ? out.left_box : out.right_box).grow(b->box[best_axis][j]);
    return out;
}

}  // namespace

TEST(SmallNode, SplitsAsTheBinnedPathDoes) {
    std::mt19937 rng(20261128);
    int kinds[3] = {0, 0, 0};
    for (int trial = 0; trial < 20000; ++trial) {
        const int n = 3 + trial % int(kSmallNodeMax - 2);
        const int bins = trial % 7 == 0 ? 2 : trial % 7 == 1 ? 5 : trial % 7 == 2 ? 64 : 16;
        const int max_leaf = trial % 3 == 0 ? 1 : trial % 3 == 1 ? 4 : 8;
        std::vector<Ref> src = records(n, trial % 4 == 3, rng);
        if (trial % 9 == 8) src.assign(src.size(), src[0]);  // one point: no bin boundary
        Box4 box, cbox;
        for (const Ref& r : src) {
            box.grow(load3(r.lo), load3(r.hi));
            cbox.grow_point(centroid(load3(r.lo), load3(r.hi)));
        }
        std::vector<Ref> want_dst(src.size()), got_dst(src.size());
        const SmallSplit want = binned(src, want_dst, box, cbox, bins, max_leaf, 1.0f);
        const SmallSplit got =
            small_split(src.data(), got_dst.data(), 0, std::uint32_t(n), box, cbox, bins, max_leaf, 1.0f);
        ++kinds[want.kind];
        ASSERT_EQ(got.kind, want.kind) << "trial " << trial << ", " << n << " records, " << bins << " bins";
        if (want.kind != SmallSplit::Split) continue;
        ASSERT_EQ(got.mid, want.mid) << "trial " << trial;
        ASSERT_EQ(std::memcmp(got_dst.data(), want_dst.data(), src.size() * sizeof(Ref)), 0) << "trial " << trial;
        EXPECT_TRUE(clpath::test::same_box_bits(got.left_box, want.left_box)) << "trial " << trial;
        EXPECT_TRUE(clpath::test::same_box_bits(got.right_box, want.right_box)) << "trial " << trial;
        EXPECT_TRUE(clpath::test::same_box_bits(got.left_cbox, want.left_cbox)) << "trial " << trial;
        EXPECT_TRUE(clpath::test::same_box_bits(got.right_cbox, want.right_cbox)) << "trial " << trial;
    }
    // Every outcome met often: the comparison above is not of one kind only.
    for (int k = 0; k < 3; ++k) EXPECT_GT(kinds[k], 200) << "outcome " << k;
}

TEST(SmallNode, ComparesBoxesToTheBit) {
    // Control: the check above tells the zeros apart.
    Box4 a, b;
    a.grow_point(splat(0.0f));
    b.grow_point(splat(-0.0f));
    EXPECT_FALSE(clpath::test::same_box_bits(a, b));
    EXPECT_TRUE(clpath::test::same_box_bits(a, a));
}
