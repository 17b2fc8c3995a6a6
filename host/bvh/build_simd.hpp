#pragma once
// Four floats at once for the BVH builder's inner loops (box growth, centroid
// bins): SSE2 on x86-64, plain arrays elsewhere. Only what the builder needs.
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace clpath::bvh_build {

#if defined(__SSE2__)
struct F4 {
    __m128 v;
};
inline F4 load4(const float* p) { return {_mm_load_ps(p)}; }  // p: 16-byte aligned
// x, y, z from p, lane 3 zeroed: the builder's records keep an integer there,
// which as a float is often denormal, and arithmetic on denormals is slow.
inline F4 load3(const float* p) {
    const __m128 mask = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
    return {_mm_and_ps(_mm_load_ps(p), mask)};
}
inline void store4(float* p, F4 a) { _mm_store_ps(p, a.v); }
inline F4 zero_lane3(F4 a) { return {_mm_and_ps(a.v, _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)))}; }
inline F4 splat(float x) { return {_mm_set1_ps(x)}; }
inline F4 set4(float x, float y, float z, float w) { return {_mm_setr_ps(x, y, z, w)}; }
inline F4 min4(F4 a, F4 b) { return {_mm_min_ps(a.v, b.v)}; }
inline F4 max4(F4 a, F4 b) { return {_mm_max_ps(a.v, b.v)}; }
inline F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline F4 operator/(F4 a, F4 b) { return {_mm_div_ps(a.v, b.v)}; }
// Truncates (x clamped to [0, top]) to integers; a NaN lane gives 0: maxps
// returns its second operand when either is NaN.
inline void bin_index4(F4 x, F4 top, std::int32_t out[4]) {
    const __m128 c = _mm_min_ps(_mm_max_ps(x.v, _mm_setzero_ps()), top.v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(c));
}
// bin_index4's x, y, z lanes, straight into registers.
inline void bin_index3(F4 x, F4 top, int& k0, int& k1, int& k2) {
    const __m128i k = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(x.v, _mm_setzero_ps()), top.v));
    k0 = _mm_cvtsi128_si32(k);
    k1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(k, 1));
    k2 = _mm_cvtsi128_si32(_mm_shuffle_epi32(k, 2));
}
// 2 (x y + y z + z x) of the x, y, z lanes, summed in that order (so equal to
// the scalar expression bit for bit), without a trip through memory.
inline float area_of_extent(F4 e) {
    const __m128 p = _mm_mul_ps(e.v, _mm_shuffle_ps(e.v, e.v, _MM_SHUFFLE(3, 0, 2, 1)));  // xy, yz, zx
    const __m128 s = _mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_shuffle_ps(p, p, 2));
    return 2.0f * _mm_cvtss_f32(s);
}
// 16 bytes at p (any alignment): a's x, y, z lanes, then the 4 bytes of w.
inline void store3_with(float* p, F4 a, std::uint32_t w) {
    const __m128 wv = _mm_castsi128_ps(_mm_cvtsi32_si128(int(w)));
    const __m128 zw = _mm_shuffle_ps(a.v, wv, _MM_SHUFFLE(0, 0, 2, 2));  // z, z, w, w
    _mm_storeu_ps(p, _mm_shuffle_ps(a.v, zw, _MM_SHUFFLE(2, 0, 1, 0)));
}
inline float lane(F4 a, int i) {
    alignas(16) float e[4];
    _mm_store_ps(e, a.v);
    return e[i];
}
// Bit i set where lane i of a >= lane i of b (false for NaN).
inline int ge_mask(F4 a, F4 b) { return _mm_movemask_ps(_mm_cmpge_ps(a.v, b.v)); }
// All lanes' bits set (when) or clear, to select with.
inline F4 lane_mask(bool when) { return {_mm_castsi128_ps(_mm_set1_epi32(-int(when)))}; }
// mask ? a : b, lane by lane (mask lanes all ones or all zeros).
inline F4 select4(F4 mask, F4 a, F4 b) { return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))}; }
#else
struct F4 {
    float v[4];
};
inline F4 load4(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
inline F4 load3(const float* p) { return {{p[0], p[1], p[2], 0.0f}}; }
inline void store4(float* p, F4 a) {
    for (int i = 0; i < 4; ++i) p[i] = a.v[i];
}
inline F4 zero_lane3(F4 a) { return {{a.v[0], a.v[1], a.v[2], 0.0f}}; }
inline F4 splat(float x) { return {{x, x, x, x}}; }
inline F4 set4(float x, float y, float z, float w) { return {{x, y, z, w}}; }
#define CLPATH_F4_OP(name, expr)              \
    inline F4 name(F4 a, F4 b) {              \
        F4 r;                                 \
        for (int i = 0; i < 4; ++i) {         \
            const float x = a.v[i], y = b.v[i]; \
            r.v[i] = (expr);                  \
        }                                     \
        return r;                             \
    }
CLPATH_F4_OP(min4, y < x ? y : x)
CLPATH_F4_OP(max4, y > x ? y : x)
CLPATH_F4_OP(operator+, x + y)
CLPATH_F4_OP(operator-, x - y)
CLPATH_F4_OP(operator*, x * y)
CLPATH_F4_OP(operator/, x / y)
#undef CLPATH_F4_OP
inline void bin_index4(F4 x, F4 top, std::int32_t out[4]) {
    for (int i = 0; i < 4; ++i) {
        float c = x.v[i] > 0.0f ? x.v[i] : 0.0f;  // NaN -> 0
        c = c < top.v[i] ? c : top.v[i];
        out[i] = std::int32_t(c);
    }
}
inline void bin_index3(F4 x, F4 top, int& k0, int& k1, int& k2) {
    std::int32_t k[4];
    bin_index4(x, top, k);
    k0 = k[0], k1 = k[1], k2 = k[2];
}
inline float area_of_extent(F4 e) { return 2.0f * (e.v[0] * e.v[1] + e.v[1] * e.v[2] + e.v[2] * e.v[0]); }
inline void store3_with(float* p, F4 a, std::uint32_t w) {
    for (int i = 0; i < 3; ++i) p[i] = a.v[i];
    std::memcpy(p + 3, &w, 4);
}
inline float lane(F4 a, int i) { return a.v[i]; }
inline int ge_mask(F4 a, F4 b) {
    int m = 0;
    for (int i = 0; i < 4; ++i) m |= int(a.v[i] >= b.v[i]) << i;
    return m;
}
inline F4 lane_mask(bool when) {
    const float f = when ? 1.0f : 0.0f;  // a flag per lane: select4 below reads it as a truth value
    return {{f, f, f, f}};
}
inline F4 select4(F4 mask, F4 a, F4 b) {
    F4 r;
    for (int i = 0; i < 4; ++i) r.v[i] = mask.v[i] != 0.0f ? a.v[i] : b.v[i];
    return r;
}
#endif

// c where keep, else +infinity, without a branch (a select on the bits).
inline float keep_or_inf(bool keep, float c) {
    const float infinity = std::numeric_limits<float>::infinity();
    std::uint32_t b, inf;
    std::memcpy(&b, &c, 4);
    std::memcpy(&inf, &infinity, 4);
    const std::uint32_t m = 0u - std::uint32_t(keep);
    b = (b & m) | (inf & ~m);
    std::memcpy(&c, &b, 4);
    return c;
}

// An axis-aligned box; lane 3 is ignored.
struct Box4 {
    F4 lo = splat(std::numeric_limits<float>::infinity());  // empty: lo > hi
    F4 hi = splat(-std::numeric_limits<float>::infinity());
    void grow(F4 l, F4 h) {
        lo = min4(lo, l);
        hi = max4(hi, h);
    }
    void grow(const Box4& b) { grow(b.lo, b.hi); }
    void grow_point(F4 p) { grow(p, p); }
};

// Surface area of a non-empty box (x, y, z lanes).
inline float area(const Box4& b) { return area_of_extent(b.hi - b.lo); }

}  // namespace clpath::bvh_build
