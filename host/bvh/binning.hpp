#pragma once
// Binning for the SAH builder (binned_builder.cpp): the bins of a node's
// triangles on all three axes, and the map from a centroid to its bin.
#include <cstdint>

#include "bvh/records.hpp"
#include "bvh/build_simd.hpp"

namespace clpath::bvh_build {

constexpr int kMaxBins = 256;
// Per axis, the bins' boxes and counts, at their position in the axis's
// BinList (below). A node over at least as many triangles as bins clears and
// fills them all (bin_refs; position = bin); a smaller node keeps
// only the bins it occupies, packed in increasing order (bin_refs_sparse), so
// nothing needs clearing: its SAH sweep visits only those bins (the same
// choice as visiting all: the costs between two occupied bins do not change,
// and the sweep keeps the first of equal costs).
struct Bins {
    Box4 box[3][kMaxBins];
    std::uint32_t count[3][kMaxBins];

    void clear(int bins) {
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < bins; ++k) {
                box[a][k] = Box4{};
                count[a][k] = 0;
            }
    }
    void merge(const Bins& o, int bins) {
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < bins; ++k) {
                box[a][k].grow(o.box[a][k]);
                count[a][k] += o.count[a][k];
            }
    }
};

// The bins an SAH sweep visits on one axis, in order.
struct BinList {
    std::uint8_t bin[kMaxBins];
    int size = 0;
};

// All bins, 0 .. bins - 1.
inline void list_all(int bins, BinList& l) {
    for (int k = 0; k < bins; ++k) l.bin[k] = std::uint8_t(k);
    l.size = bins;
}

inline F4 centroid(F4 lo, F4 hi) {
    const F4 half = splat(0.5f);
    return lo * half + hi * half;  // not (lo + hi) / 2: no overflow near the float range's ends
}

// The mapping from a centroid to its bin on each axis (Wald 2007: equal slabs
// of the node's centroid bounds). Binning and partitioning both use it, so a
// partition puts exactly the binned counts on each side.
struct BinMap {
    F4 lo, scale, top;
    int bins;
    BinMap(const Box4& cbox, int bins) : bins(bins) {
        // One division per lane, as b / max(extent, 1e-30) per axis; lane 3
        // zeroed in a register (through memory, a 4-byte store then a 16-byte
        // load of the same bytes stalled every node: no store forwarding).
        const F4 e = max4(cbox.hi - cbox.lo, splat(1e-30f));
        lo = cbox.lo;
        scale = zero_lane3(splat(float(bins)) / e);
        top = splat(float(bins - 1));
    }
    // Whether centroid c's bin on axis is <= bin, for bin < bins - 1: the
    // bin index is the truncation of (c - lo) * scale clamped to [0, top]
    // (NaN to 0), so it exceeds bin exactly when that product is >= bin + 1.
    bool left_of(F4 c, int axis, int bin) const { return !((ge_mask((c - lo) * scale, splat(float(bin + 1))) >> axis) & 1); }
};

// Bins records [begin, end) into bins (map.bins of them per axis, cleared first):
// bin_refs_avx where the CPU has AVX, else bin_refs_portable. Both give the
// same bins bit for bit.
void bin_refs(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins);
void bin_refs_portable(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins);
// False where this CPU (or this build's target) has no AVX; bin_refs_avx must not be called then.
bool avx_available();
void bin_refs_avx(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins);

// bin_refs for a node over fewer triangles than bins: fills lists[a] with
// the occupied bins of axis a, and bins' entries [0, lists[a].size) with
// their boxes and counts; nothing needs clearing before.
void bin_refs_sparse(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& b,
                     BinList* lists);

// bin_refs_sparse for records begin and begin + 1, the same result sooner
// (a node over two triangles is the commonest kind).
void bin_refs_pair(const Ref* r, std::uint32_t begin, const BinMap& map, Bins& b, BinList* lists);

}  // namespace clpath::bvh_build
