#include "bvh/small_node.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "bvh/binning.hpp"

// Before a loop with a fixed trip count in split<N> (see there).
#define CLPATH_UNROLL _Pragma("GCC unroll 64")

namespace clpath::bvh_build {
namespace {

// The compare-exchanges of Batcher's odd-even merge sort (Knuth, TAOCP 3,
// 5.3.4) of width keys, width a power of two.
struct Network {
    int size = 0;
    std::uint8_t lo[64]{}, hi[64]{};
};

constexpr Network odd_even_merge_sort(int width) {
    Network net;
    for (int p = 1; p < width; p <<= 1)
        for (int q = p; q >= 1; q >>= 1)
            for (int j = q % p; j + q < width; j += 2 * q)
                for (int i = 0; i < q && i < width - j - q; ++i)
                    if ((i + j) / (2 * p) == (i + j + q) / (2 * p)) {
                        net.lo[net.size] = std::uint8_t(i + j);
                        net.hi[net.size] = std::uint8_t(i + j + q);
                        ++net.size;
                    }
    return net;
}

// Why the result is the binned path's: a bin boundary's cost depends only on
// which records lie left of it (a union of boxes has the same value whatever
// the order; only the sign of a zero bound can differ, and that changes no
// area), and the binned sweep visits the occupied bins' boundaries in
// increasing order, keeping the first of equal costs, as the walk over the
// records sorted by bin does below. Where the order does show (which of +0
// and -0 a bound keeps: min and max keep their second operand on ties), it is
// the binned path's: a child's box grows over its records by bin, then by
// index (the bins' order, and each bin's own), and its centroid bounds by
// index (partition_refs's order).
//
// N is a template parameter so that every loop has a fixed trip count (no
// loop exit to mispredict), the sorting network's indices are constants (its
// keys stay in registers, each exchange a min and a max), and the cheapest
// boundary is found without a data-dependent branch: in a first version with
// loops over n, a sort and a running minimum, the branches missed often
// enough to cost more than the binned path.
template <int N>
SmallSplit split(const Ref* src, Ref* dst, std::uint32_t begin, const Box4& box, const Box4& cbox, int bins,
                 int max_leaf_size, float traversal_cost) {
    SmallSplit out;
    const F4 ext4 = cbox.hi - cbox.lo;
    const float ext[3] = {lane(ext4, 0), lane(ext4, 1), lane(ext4, 2)};
    const int axis_long = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : (ext[1] >= ext[2] ? 1 : 2);
    if (!(ext[axis_long] > 0)) return out;  // all centroids at one point: no bin boundary
    F4 lo[N], hi[N], c[N];
    int k[3][N];
    const BinMap map(cbox, bins);
    CLPATH_UNROLL
    for (int i = 0; i < N; ++i) {
        lo[i] = load3(src[begin + i].lo);
        hi[i] = load3(src[begin + i].hi);
        c[i] = centroid(lo[i], hi[i]);
        bin_index3((c[i] - map.lo) * map.scale, map.top, k[0][i], k[1][i], k[2][i]);
    }
    // Per axis, the records by bin, then by index: keys bin x 16 + index (all
    // different), padded to the network's width with the largest key.
    constexpr int W = N <= 4 ? 4 : N <= 8 ? 8 : 16;
    constexpr Network net = odd_even_merge_sort(W);
    int order[3][N];
    float cost[3][N - 1];  // of the boundary after sorted position j; +inf: none there
    CLPATH_UNROLL
    for (int a = 0; a < 3; ++a) {
        int key[W];
        CLPATH_UNROLL
        for (int i = 0; i < W; ++i) key[i] = i < N ? k[a][i] << 4 | i : std::numeric_limits<int>::max();
        CLPATH_UNROLL
        for (int e = 0; e < net.size; ++e) {
            const int x = key[net.lo[e]], y = key[net.hi[e]];
            key[net.lo[e]] = std::min(x, y);
            key[net.hi[e]] = std::max(x, y);
        }
        int* o = order[a];
        CLPATH_UNROLL
        for (int j = 0; j < N; ++j) o[j] = key[j] & 15;
        float right_cost[N];
        Box4 right;
        CLPATH_UNROLL
        for (int j = N - 1; j > 0; --j) {
            right.grow(lo[o[j]], hi[o[j]]);
            right_cost[j] = area_of_extent(right.hi - right.lo) * float(N - j);
        }
        Box4 left;
        CLPATH_UNROLL
        for (int j = 0; j < N - 1; ++j) {
            left.grow(lo[o[j]], hi[o[j]]);
            const float cj = area_of_extent(left.hi - left.lo) * float(j + 1) + right_cost[j + 1];
            // Only between bins, and on an axis the centroids spread along.
            cost[a][j] = keep_or_inf((key[j] >> 4 != key[j + 1] >> 4) & (ext[a] > 0), cj);
        }
    }
    // The first of the cheapest, in the binned sweeps' order (axis, then
    // boundary): the minimum, then the first cost equal to it. A cost that is
    // +inf (or NaN) is never taken, as the sweep's strict "cheaper" never takes it.
    float best_cost = std::numeric_limits<float>::infinity();
    CLPATH_UNROLL
    for (int t = 0; t < 3 * (N - 1); ++t) {
        const float ct = cost[t / (N - 1)][t % (N - 1)];
        best_cost = ct < best_cost ? ct : best_cost;  // minss: a NaN is passed over
    }
    std::uint32_t at_min = 0;
    CLPATH_UNROLL
    for (int t = 0; t < 3 * (N - 1); ++t) at_min |= std::uint32_t(cost[t / (N - 1)][t % (N - 1)] == best_cost) << t;
    const bool found = best_cost < std::numeric_limits<float>::infinity();
    const int best = found ? __builtin_ctz(at_min) : 0;
    const int best_axis = best / (N - 1), best_left = best % (N - 1) + 1;
    const float node_area = area(box);
    const float split_cost = traversal_cost + (node_area > 0 ? best_cost / node_area : 0.0f);
    if (N <= max_leaf_size && (!found || float(N) <= split_cost)) {
        out.kind = SmallSplit::Leaf;
        return out;
    }
    if (!found) return out;
    out.kind = SmallSplit::Split;
    const int* o = order[best_axis];
    const int best_bin = k[best_axis][o[best_left - 1]];
    CLPATH_UNROLL
    for (int j = 0; j < N; ++j) (j < best_left ? out.left_box : out.right_box).grow(lo[o[j]], hi[o[j]]);
    // As partition_portable: one store per record at the cursor its side
    // selects, and each side's centroid bounds grown through selects. Written
    // out here for its fixed trip count: calling partition_refs instead, with
    // its loop over n, took 11 % more branch misses in the whole build.
    const F4 inf = splat(std::numeric_limits<float>::infinity()), ninf = splat(-std::numeric_limits<float>::infinity());
    F4 llo = inf, lhi = ninf, rlo = inf, rhi = ninf;
    std::uint32_t l = begin, r = begin + N - 1;
    CLPATH_UNROLL
    for (int i = 0; i < N; ++i) {
        const std::uint32_t right = k[best_axis][i] > best_bin;
        dst[l + ((r - l) & (0u - right))] = src[begin + i];
        l += 1u - right;
        r -= right;
        const F4 m = lane_mask(right != 0);
        llo = min4(llo, select4(m, inf, c[i]));
        lhi = max4(lhi, select4(m, ninf, c[i]));
        rlo = min4(rlo, select4(m, c[i], inf));
        rhi = max4(rhi, select4(m, c[i], ninf));
    }
    out.left_cbox.lo = llo;
    out.left_cbox.hi = lhi;
    out.right_cbox.lo = rlo;
    out.right_cbox.hi = rhi;
    out.mid = l;
    return out;
}

}  // namespace

SmallSplit small_split(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, const Box4& box,
                       const Box4& cbox, int bins, int max_leaf_size, float traversal_cost) {
    static_assert(kSmallNodeMax == 8, "one case below per size");
    switch (end - begin) {
        case 3: return split<3>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        case 4: return split<4>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        case 5: return split<5>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        case 6: return split<6>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        case 7: return split<7>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        case 8: return split<8>(src, dst, begin, box, cbox, bins, max_leaf_size, traversal_cost);
        default: return {};
    }
}

}  // namespace clpath::bvh_build
