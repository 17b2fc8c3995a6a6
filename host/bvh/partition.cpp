#include "bvh/partition.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define CLPATH_BVH_HAVE_AVX_PATH 1
#include <immintrin.h>
#endif

namespace clpath::bvh_build {

// One store per record, at the cursor its side selects by arithmetic (no
// branch to mispredict, and half the stores of writing every record at both
// cursors), and the sides' centroid bounds grown through selects.
std::uint32_t partition_portable(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end,
                                 std::uint32_t left_at, std::uint32_t right_at, std::uint32_t right_step,
                                 const BinMap& map, int axis, int bin, Box4& lcb, Box4& rcb) {
    std::uint32_t l = left_at, r = right_at;
    const F4 t = splat(float(bin + 1)), inf = splat(std::numeric_limits<float>::infinity()),
             ninf = splat(-std::numeric_limits<float>::infinity());
    F4 llo = inf, lhi = ninf, rlo = inf, rhi = ninf;
    for (std::uint32_t i = begin; i < end; ++i) {
        const F4 lo = load3(src[i].lo), hi = load3(src[i].hi), c = centroid(lo, hi);
        const std::uint32_t right = std::uint32_t(ge_mask((c - map.lo) * map.scale, t) >> axis) & 1u;
        const std::uint32_t all = 0u - right;
        const F4 m = lane_mask(right != 0);
        dst[l + ((r - l) & all)] = src[i];
        l += 1u - right;
        r += right_step & all;
        llo = min4(llo, select4(m, inf, c));
        lhi = max4(lhi, select4(m, ninf, c));
        rlo = min4(rlo, select4(m, c, inf));
        rhi = max4(rhi, select4(m, c, ninf));
    }
    lcb.lo = llo;
    lcb.hi = lhi;
    rcb.lo = rlo;
    rcb.hi = rhi;
    return l;
}

#if CLPATH_BVH_HAVE_AVX_PATH
// m ? b : a, lane by lane (m's lanes all ones or all zeros). In inline asm
// because GCC 12 rewrites _mm256_blendv_ps as a test of m's sign bits and,
// with AVX but no AVX2, does that test lane by lane in scalar registers.
__attribute__((target("avx"), always_inline)) inline __m256 blend(__m256 a, __m256 b, __m256 m) {
    __m256 r;
    __asm__("vblendvps %3, %2, %1, %0" : "=x"(r) : "x"(a), "x"(b), "x"(m));
    return r;
}

// The same with a record as one 256-bit value (one load, one store), and
// each side's centroid bounds as one 256-bit value, lo then hi negated, so
// one blend and one min grow both halves (-max(a, b) = min(-a, -b)); the
// idea of tinybvh's BuildAVX (Bikker, tinybvh 1.6) for its bins. minps keeps
// its second operand on ties as the portable min4 and max4 do, so the
// bounds agree bit for bit, signed zeros too. The centroid and the test are
// the same SSE operations as centroid() and BinMap's, without FMA (target
// avx alone), so every record goes to the same side. noipa: GCC otherwise
// clones it into its callers and schedules the clone worse.
template <bool Stream>
__attribute__((target("avx"), always_inline)) inline std::uint32_t partition_avx_loop(
    const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at, std::uint32_t right_at,
    std::uint32_t right_step, const BinMap& map, int axis, int bin, Box4& lcb, Box4& rcb) {
    static_assert(sizeof(Ref) == 32, "a record is one 256-bit value");
    const __m256 keep6 = _mm256_castsi256_ps(_mm256_setr_epi32(-1, -1, -1, 0, -1, -1, -1, 0));
    const __m256 flip_hi = _mm256_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, -0.0f, -0.0f, -0.0f, -0.0f);
    const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    alignas(16) float m[8];
    store4(m, map.lo);
    store4(m + 4, map.scale);
    const __m128 mlo = _mm_load_ps(m), mscale = _mm_load_ps(m + 4);
    const __m128 half = _mm_set1_ps(0.5f), t = _mm_set1_ps(float(bin + 1));
    const __m128i pick = _mm_set1_epi32(axis);  // vpermilps: lane axis into every lane
    __m256 lacc = inf, racc = inf;  // [lo = +inf, -hi = -(-inf)]: empty
    // The cursors as byte offsets (no scaling per record), 64-bit (a
    // range of 2^31 records spans 64 GiB), and the side read from the lane
    // already broadcast for the blends (no shift by a variable count, which
    // costs three micro-ops on Intel): the loop issues micro-ops as fast as
    // the core takes them, so each one saved shows.
    char* const out_base = reinterpret_cast<char*>(dst);
    std::size_t l = std::size_t(left_at) * sizeof(Ref), r = std::size_t(right_at) * sizeof(Ref);
    const std::size_t step = right_step == 1u ? sizeof(Ref) : std::size_t(0) - sizeof(Ref);
    for (std::uint32_t i = begin; i < end; ++i) {
        const __m256 f = _mm256_loadu_ps(src[i].lo);
        const __m256 fm = _mm256_and_ps(f, keep6);
        const __m128 c = _mm_add_ps(_mm_mul_ps(_mm256_castps256_ps128(fm), half),
                                    _mm_mul_ps(_mm256_extractf128_ps(fm, 1), half));
        const __m128 ge = _mm_cmpge_ps(_mm_mul_ps(_mm_sub_ps(c, mlo), mscale), t);
        const __m128 m4 = _mm_permutevar_ps(ge, pick);
        const std::size_t all = std::size_t(0) - std::size_t(_mm_movemask_ps(m4) & 1);
        float* const to = reinterpret_cast<float*>(out_base + l + ((r - l) & all));
        if constexpr (Stream)
            _mm256_stream_ps(to, f);
        else
            _mm256_storeu_ps(to, f);
        l += sizeof(Ref) & ~all;
        r += step & all;
        const __m256 m8 = _mm256_insertf128_ps(_mm256_castps128_ps256(m4), m4, 1);
        const __m256 cc = _mm256_xor_ps(_mm256_insertf128_ps(_mm256_castps128_ps256(c), c, 1), flip_hi);
        lacc = _mm256_min_ps(lacc, blend(cc, inf, m8));
        racc = _mm256_min_ps(racc, blend(inf, cc, m8));
    }
    alignas(32) float out[16];
    _mm256_store_ps(out, _mm256_xor_ps(lacc, flip_hi));
    _mm256_store_ps(out + 8, _mm256_xor_ps(racc, flip_hi));
    lcb.lo = load4(out);
    lcb.hi = load4(out + 4);
    rcb.lo = load4(out + 8);
    rcb.hi = load4(out + 12);
    if constexpr (Stream) _mm_sfence();  // the streaming stores ordered before the threads' join
    return std::uint32_t(l / sizeof(Ref));
}

// Streaming (non-temporal) stores where asked and dst is 32-byte aligned:
// a big node's scatter writes tens of megabytes that the next pass reads
// from memory anyway, so a normal store's read of each line before writing
// it (and the lines it evicts from the cache) is wasted traffic.
// noipa: GCC otherwise clones it into its callers and schedules the clone worse.
__attribute__((target("avx"), noipa)) std::uint32_t partition_avx(const Ref* src, Ref* dst, std::uint32_t begin,
                                                                   std::uint32_t end, std::uint32_t left_at,
                                                                   std::uint32_t right_at, std::uint32_t right_step,
                                                                   const BinMap& map, int axis, int bin, Box4& lcb,
                                                                   Box4& rcb, bool stream) {
    if (stream && (reinterpret_cast<std::uintptr_t>(dst) & 31) == 0)
        return partition_avx_loop<true>(src, dst, begin, end, left_at, right_at, right_step, map, axis, bin, lcb, rcb);
    return partition_avx_loop<false>(src, dst, begin, end, left_at, right_at, right_step, map, axis, bin, lcb, rcb);
}
#else
std::uint32_t partition_avx(const Ref*, Ref*, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t,
                            std::uint32_t, const BinMap&, int, int, Box4&, Box4&, bool) {
    throw std::logic_error("partition_avx: no AVX path in this build");
}
#endif

namespace {
std::uint32_t partition(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at,
                        std::uint32_t right_at, std::uint32_t right_step, const BinMap& map, int axis, int bin,
                        Box4& lcb, Box4& rcb, bool stream) {
    return avx_available() ? partition_avx(src, dst, begin, end, left_at, right_at, right_step, map, axis, bin, lcb, rcb,
                                           stream)
                           : partition_portable(src, dst, begin, end, left_at, right_at, right_step, map, axis, bin,
                                                lcb, rcb);
}
}  // namespace

std::uint32_t partition_refs(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, const BinMap& map,
                             int axis, int bin, Box4& lcb, Box4& rcb) {
    return partition(src, dst, begin, end, begin, end - 1, ~0u, map, axis, bin, lcb, rcb, false);
}

void scatter_refs_stable(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at,
                         std::uint32_t right_at, const BinMap& map, int axis, int bin, Box4& lcb, Box4& rcb) {
    partition(src, dst, begin, end, left_at, right_at, 1u, map, axis, bin, lcb, rcb, true);
}

}  // namespace clpath::bvh_build
