#include "bvh/binning.hpp"

#include <limits>
#include <stdexcept>

// AVX is used where the CPU has it, whatever the compiler's target: the
// function below is compiled for AVX alone and chosen at run time, so the
// binary still runs on an x86-64 without it.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define CLPATH_BVH_HAVE_AVX_PATH 1
#include <immintrin.h>
#endif

namespace clpath::bvh_build {

constexpr std::uint32_t kSetsFrom = 128;
constexpr int kSets = 4;
// bin_refs_avx's sets packed for this many bins (BvhBuildOptions's default) or fewer.
constexpr int kPackedBins = 16;

// From kSetsFrom triangles on, triangles go round robin to four sets of
// bins, merged at the end as (set 0 + set 1) + (set 2 + set 3): a run of
// triangles in one bin (neighbours in a mesh often are) would otherwise chain
// every update through the same memory. Two sets left half of that chain
// (12.3 ns a record on a coherent mesh against 7.6 with four, Xeon, L2).
// bin_refs_avx splits them the same way and merges in the same order, so the
// two agree bit for bit (min and max keep their second operand on ties, so
// the order decides a bound's sign where -0 and +0 meet).
void bin_refs_portable(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins) {
    bins.clear(map.bins);
    struct Raw {  // Box4 without its initialisers: only map.bins of them are set, below
        F4 lo, hi;
    };
    Raw aux_box[kSets - 1][3][kMaxBins];  // sets 1..3; set 0 is bins itself
    std::uint32_t aux_count[kSets - 1][3][kMaxBins];
    for (int set = 0; set < kSets - 1; ++set)
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < map.bins; ++k) {
                aux_box[set][a][k].lo = Box4{}.lo;
                aux_box[set][a][k].hi = Box4{}.hi;
                aux_count[set][a][k] = 0;
            }
    auto put = [&map, r](std::uint32_t i, auto* b0, auto* b1, auto* b2, std::uint32_t* c0, std::uint32_t* c1,
                         std::uint32_t* c2) {
        const F4 lo = load3(r[i].lo), hi = load3(r[i].hi);
        int k0, k1, k2;
        bin_index3((centroid(lo, hi) - map.lo) * map.scale, map.top, k0, k1, k2);
        b0[k0].lo = min4(b0[k0].lo, lo);
        b0[k0].hi = max4(b0[k0].hi, hi);
        ++c0[k0];
        b1[k1].lo = min4(b1[k1].lo, lo);
        b1[k1].hi = max4(b1[k1].hi, hi);
        ++c1[k1];
        b2[k2].lo = min4(b2[k2].lo, lo);
        b2[k2].hi = max4(b2[k2].hi, hi);
        ++c2[k2];
    };
    auto put_aux = [&](std::uint32_t i, int set) {
        put(i, aux_box[set - 1][0], aux_box[set - 1][1], aux_box[set - 1][2], aux_count[set - 1][0],
            aux_count[set - 1][1], aux_count[set - 1][2]);
    };
    std::uint32_t i = begin;
    if (end - begin >= kSetsFrom)
        for (; i + kSets - 1 < end; i += kSets) {
            put(i, bins.box[0], bins.box[1], bins.box[2], bins.count[0], bins.count[1], bins.count[2]);
            for (int set = 1; set < kSets; ++set) put_aux(i + std::uint32_t(set), set);
        }
    for (; i < end; ++i) put(i, bins.box[0], bins.box[1], bins.box[2], bins.count[0], bins.count[1], bins.count[2]);
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < map.bins; ++k) {
            Box4 high;  // set 2 + set 3
            high.lo = min4(aux_box[1][a][k].lo, aux_box[2][a][k].lo);
            high.hi = max4(aux_box[1][a][k].hi, aux_box[2][a][k].hi);
            bins.box[a][k].grow(aux_box[0][a][k].lo, aux_box[0][a][k].hi);  // set 0 + set 1
            bins.box[a][k].grow(high.lo, high.hi);
            bins.count[a][k] += aux_count[0][a][k] + aux_count[1][a][k] + aux_count[2][a][k];
        }
}

void bin_refs_sparse(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& b,
                     BinList* lists) {
    // First pass: each triangle's bins, and which bins are occupied. Second:
    // each occupied bin's rank among them, then the boxes grown in triangle
    // order (as binning into the bins themselves would), with no branch on
    // whether a bin was seen before.
    const std::uint32_t n = end - begin;
    std::uint8_t bin_of[3][kMaxBins];  // n < bins <= kMaxBins
    std::uint8_t rank[3][kMaxBins];
    const int words = (map.bins + 63) / 64;
    // Bins 0-63 of each axis in registers (every bin with the default 16):
    // in memory, each record's three updates waited on the last record's.
    std::uint64_t occupied[3][kMaxBins / 64], low[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a)
        for (int w = 0; w < words; ++w) occupied[a][w] = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const F4 lo = load3(r[begin + i].lo), hi = load3(r[begin + i].hi);
        int k[3];
        bin_index3((centroid(lo, hi) - map.lo) * map.scale, map.top, k[0], k[1], k[2]);
        for (int a = 0; a < 3; ++a) {
            bin_of[a][i] = std::uint8_t(k[a]);
            if (k[a] < 64)
                low[a] |= std::uint64_t(1) << k[a];
            else
                occupied[a][k[a] >> 6] |= std::uint64_t(1) << (k[a] & 63);
        }
    }
    for (int a = 0; a < 3; ++a) {
        occupied[a][0] |= low[a];
        BinList& l = lists[a];
        l.size = 0;
        for (int w = 0; w < words; ++w)
            for (std::uint64_t m = occupied[a][w]; m; m &= m - 1) {
                const int k = w * 64 + __builtin_ctzll(m);
                rank[a][k] = std::uint8_t(l.size);
                l.bin[l.size] = std::uint8_t(k);
                b.box[a][l.size] = Box4{};
                b.count[a][l.size] = 0;
                ++l.size;
            }
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        const F4 lo = load3(r[begin + i].lo), hi = load3(r[begin + i].hi);
        for (int a = 0; a < 3; ++a) {
            const int j = rank[a][bin_of[a][i]];
            b.box[a][j].grow(lo, hi);
            ++b.count[a][j];
        }
    }
}

void bin_refs_pair(const Ref* r, std::uint32_t begin, const BinMap& map, Bins& b, BinList* lists) {
    const F4 lo0 = load3(r[begin].lo), hi0 = load3(r[begin].hi), lo1 = load3(r[begin + 1].lo),
             hi1 = load3(r[begin + 1].hi);
    int k0[3], k1[3];
    bin_index3((centroid(lo0, hi0) - map.lo) * map.scale, map.top, k0[0], k0[1], k0[2]);
    bin_index3((centroid(lo1, hi1) - map.lo) * map.scale, map.top, k1[0], k1[1], k1[2]);
    for (int a = 0; a < 3; ++a) {
        BinList& l = lists[a];
        Box4* box = b.box[a];
        std::uint32_t* count = b.count[a];
        if (k0[a] == k1[a]) {  // one bin, grown in record order as bin_refs_sparse grows it
            l.size = 1;
            l.bin[0] = std::uint8_t(k0[a]);
            box[0] = Box4{};
            box[0].grow(lo0, hi0);
            box[0].grow(lo1, hi1);
            count[0] = 2;
            continue;
        }
        const bool swap = k1[a] < k0[a];
        l.size = 2;
        l.bin[0] = std::uint8_t(swap ? k1[a] : k0[a]);
        l.bin[1] = std::uint8_t(swap ? k0[a] : k1[a]);
        box[swap ? 1 : 0] = Box4{};
        box[swap ? 1 : 0].grow(lo0, hi0);
        box[swap ? 0 : 1] = Box4{};
        box[swap ? 0 : 1].grow(lo1, hi1);
        count[0] = count[1] = 1;
    }
}

#if CLPATH_BVH_HAVE_AVX_PATH
bool avx_available() {
    static const bool yes = __builtin_cpu_supports("avx");
    return yes;
}

// Each bin's box as one 256-bit value, its low half lo negated and its high
// half hi, so one max grows both (-min(a, b) = max(-a, -b)), as tinybvh's
// BuildAVX keeps its bins (Bikker, tinybvh 1.6). A Box4 is lo then hi, 32
// bytes, so the bins are negated in place on the way in and out. maxps keeps
// its second operand on ties, as minps does, so the bins equal
// bin_refs_portable's bit for bit (signed zeros too). The centroid and bin
// index are the same SSE operations as BinMap's, so the partition agrees.
//
// All four sets of bins, boxes and counts, live in this function's frame, so
// every update addresses them from the stack pointer and a bin's byte offset
// (no base pointers to keep in registers: GCC spilled and reloaded the
// twelve of them per record), with the bin indices zero-extended (unsigned)
// rather than sign-extended. The result is copied into bins at the end.
//
// The sets are sized for Cap bins (the map's count or more): sized for
// kMaxBins, each axis's 16 bins sat 8 KiB after the last's, so all twelve
// (set, axis) rows fell on the same eight L1 sets and the same 4 KiB
// offsets (an L1 way apiece, and loads held back by unrelated stores: 4K
// aliasing); packed for 16, binning took 7.3 ns a record where it took 9.0
// (Xeon, coherent records, in L2; median of runs).
template <int Cap>
__attribute__((target("avx"), always_inline)) inline void bin_refs_avx_sized(const Ref* r, std::uint32_t begin,
                                                                            std::uint32_t end, const BinMap& map,
                                                                            Bins& bins) {
    const __m256 keep6 = _mm256_castsi256_ps(_mm256_setr_epi32(-1, -1, -1, 0, -1, -1, -1, 0));
    const __m256 flip_lo = _mm256_setr_ps(-0.0f, -0.0f, -0.0f, -0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    static_assert(sizeof(Box4) == 32, "a bin's box is lo then hi, 8 floats");
    alignas(16) float m[12];
    store4(m, map.lo);
    store4(m + 4, map.scale);
    store4(m + 8, map.top);
    const __m128 mlo = _mm_load_ps(m), mscale = _mm_load_ps(m + 4), mtop = _mm_load_ps(m + 8);
    const __m128 half = _mm_set1_ps(0.5f);
    // [set][axis][bin]: from kSetsFrom on, records go round robin to the sets.
    alignas(32) float box[kSets][3][Cap][8];
    std::uint32_t count[kSets][3][Cap];
    const __m256 empty = _mm256_set1_ps(-std::numeric_limits<float>::infinity());  // a negated empty box
    // A node under kSetsFrom uses set 0 alone: the others are neither
    // cleared nor merged (merging empty sets changes no bit).
    const int sets = end - begin >= kSetsFrom ? kSets : 1;
    for (int set = 0; set < sets; ++set)
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < map.bins; ++k) {
                _mm256_store_ps(box[set][a][k], empty);
                count[set][a][k] = 0;
            }
    auto put = [&](std::uint32_t i, int set) __attribute__((target("avx"), always_inline)) {
        const __m256 f = _mm256_and_ps(_mm256_loadu_ps(r[i].lo), keep6);
        const __m128 lo = _mm256_castps256_ps128(f), hi = _mm256_extractf128_ps(f, 1);
        const __m128 c = _mm_add_ps(_mm_mul_ps(lo, half), _mm_mul_ps(hi, half));
        const __m128 x = _mm_mul_ps(_mm_sub_ps(c, mlo), mscale);
        const __m128i k = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(x, _mm_setzero_ps()), mtop));
        // In [0, bins): unsigned, so the addressing needs no sign extension.
        const std::uint32_t k0 = std::uint32_t(_mm_cvtsi128_si32(k)), k1 = std::uint32_t(_mm_extract_epi32(k, 1)),
                            k2 = std::uint32_t(_mm_extract_epi32(k, 2));
        const __m256 g = _mm256_xor_ps(f, flip_lo);
        float* p0 = box[set][0][k0];
        float* p1 = box[set][1][k1];
        float* p2 = box[set][2][k2];
        _mm256_store_ps(p0, _mm256_max_ps(_mm256_load_ps(p0), g));
        ++count[set][0][k0];
        _mm256_store_ps(p1, _mm256_max_ps(_mm256_load_ps(p1), g));
        ++count[set][1][k1];
        _mm256_store_ps(p2, _mm256_max_ps(_mm256_load_ps(p2), g));
        ++count[set][2][k2];
    };
    std::uint32_t i = begin;
    static_assert(kSets == 4, "the loop and the merge below are written out for four sets");
    if (end - begin >= kSetsFrom)
        for (; i + 3 < end; i += 4) {
            put(i, 0);
            put(i + 1, 1);
            put(i + 2, 2);
            put(i + 3, 3);
        }
    for (; i < end; ++i) put(i, 0);
    if (sets == 1) {
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < map.bins; ++k) {
                _mm256_storeu_ps(reinterpret_cast<float*>(&bins.box[a][k]),
                                 _mm256_xor_ps(_mm256_load_ps(box[0][a][k]), flip_lo));
                bins.count[a][k] = count[0][a][k];
            }
        return;
    }
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < map.bins; ++k) {
            const __m256 low = _mm256_max_ps(_mm256_load_ps(box[0][a][k]), _mm256_load_ps(box[1][a][k]));
            const __m256 high = _mm256_max_ps(_mm256_load_ps(box[2][a][k]), _mm256_load_ps(box[3][a][k]));
            _mm256_storeu_ps(reinterpret_cast<float*>(&bins.box[a][k]), _mm256_xor_ps(_mm256_max_ps(low, high), flip_lo));
            bins.count[a][k] = count[0][a][k] + count[1][a][k] + count[2][a][k] + count[3][a][k];
        }
}

// noipa: GCC otherwise clones it into its callers and schedules the clone worse.
__attribute__((target("avx"), noipa)) void bin_refs_avx(const Ref* r, std::uint32_t begin, std::uint32_t end,
                                                          const BinMap& map, Bins& bins) {
    if (map.bins <= kPackedBins)
        bin_refs_avx_sized<kPackedBins>(r, begin, end, map, bins);
    else
        bin_refs_avx_sized<kMaxBins>(r, begin, end, map, bins);
}
#else
bool avx_available() { return false; }
void bin_refs_avx(const Ref*, std::uint32_t, std::uint32_t, const BinMap&, Bins&) {
    throw std::logic_error("bin_refs_avx: no AVX path in this build");
}
#endif

void bin_refs(const Ref* r, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins) {
    if (avx_available())
        bin_refs_avx(r, begin, end, map, bins);
    else
        bin_refs_portable(r, begin, end, map, bins);
}

}  // namespace clpath::bvh_build
