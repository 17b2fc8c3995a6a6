/* The film: a running sum per pixel, and the resolve that turns it into an image. */
#ifndef CLP_FILM_CL
#define CLP_FILM_CL

#include "common.h"

/* Kahan (1965) compensated addition: the error of each float addition is kept
 * in comp and fed back, so the sum of a million samples is as exact as one add. */
static inline void kahan_add(float3* sum, float3* comp, float3 x) {
    float3 y = x - *comp;
    float3 t = *sum + y;
    *comp = (t - *sum) - y;
    *sum = t;
}

/* The same for one float: the adaptive sampler's half film (film w lanes). */
static inline void kahan_add1(float* sum, float* comp, float x) {
    float y = x - *comp;
    float t = *sum + y;
    *comp = (t - *sum) - y;
    *sum = t;
}

/* sRGB transfer function (IEC 61966-2-1). */
static inline float srgb_encode(float x) {
    x = clamp(x, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}

/* mean = sum / samples, times exposure; writes linear RGBA float (alpha 1) and
 * 8-bit sRGB RGBA. */
kernel void film_resolve(global const AccumPixel* accum, uint count, float inv_samples, float exposure,
                         global float4* linear, global uchar4* srgb) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float3 s = load3g(accum[i].sum) - load3g(accum[i].comp);
    float3 c = s * inv_samples * exposure;
    linear[i] = (float4)(c, 1.0f);
    /* +0.5: round to nearest rather than truncate. */
    srgb[i] = (uchar4)((uchar)(srgb_encode(c.x) * 255.0f + 0.5f), (uchar)(srgb_encode(c.y) * 255.0f + 0.5f),
                       (uchar)(srgb_encode(c.z) * 255.0f + 0.5f), (uchar)255);
}

/* ---- exact accumulation on the device ------------------------------------
 * A chunk's compensated float sums (sum - comp) converted exactly into signed
 * 128-bit fixed point (2^-64 units) and added as integers, as the host's
 * ExactFilm does (host/render/exact_film.hpp), so the device keeps the
 * running image and only checkpoints and the end read it back. A 128-bit
 * value is a ulong2 (x: low 64 bits, y: high 64 bits, two's complement). */

/* f * 2^64 as 128 bits, exact for |f| in [2^-41, 2^63), smaller magnitudes
 * truncated towards zero; *bad set for non-finite values and |f| >= 2^63. */
static inline ulong2 fixed_from_float(float f, uint* bad) {
    uint bits = as_uint(f);
    int biased = (int)((bits >> 23) & 0xffu);
    if (biased == 0xff) {
        *bad |= 1u;
        return (ulong2)(0);
    }
    ulong m = (ulong)((bits & 0x7fffffu) | (biased ? 0x800000u : 0u));
    int shift = (biased ? biased : 1) - 150 + 64;
    if (shift + 24 > 127) {
        *bad |= 2u;
        return (ulong2)(0);
    }
    ulong2 v;
    if (shift >= 64) {
        v = (ulong2)(0, m << (shift - 64));
    } else if (shift > 40) {
        v = (ulong2)(m << shift, m >> (64 - shift));
    } else if (shift >= 0) {
        v = (ulong2)(m << shift, 0);
    } else {
        v = (ulong2)(shift > -32 ? m >> -shift : 0, 0);
    }
    if (bits >> 31) { /* -v: complement and add one */
        v = ~v;
        v.x += 1;
        v.y += v.x == 0;
    }
    return v;
}

static inline ulong2 add128(ulong2 a, ulong2 b) {
    ulong lo = a.x + b.x;
    return (ulong2)(lo, a.y + b.y + (lo < a.x));
}

static inline ulong2 neg128(ulong2 a) {
    a = ~a;
    a.x += 1;
    a.y += a.x == 0;
    return a;
}

/* exact[3i + c] += fixed(sum_c) - fixed(comp_c) for each pixel i, then the
 * chunk film is emptied for the next chunk. error: bit 0 a non-finite sum,
 * bit 1 one too large to hold; the pixel is left as it was. */
kernel void film_add_exact(global AccumPixel* accum, uint count, global ulong2* exact, global uint* error) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint bad = 0;
    ulong2 d[3];
    for (int c = 0; c < 3; ++c) {
        d[c] = fixed_from_float(accum[i].sum[c], &bad);
        /* A chunk of one sample (the default chunk of renders up to 127
         * samples per pixel) leaves every compensation zero, and zero's fixed
         * point is zero (of either sign): half the conversions skipped. */
        const float comp = accum[i].comp[c];
        if (comp != 0.0f) d[c] = add128(d[c], neg128(fixed_from_float(comp, &bad)));
    }
    if (bad) {
        atomic_or(error, bad);
        return;
    }
    for (int c = 0; c < 3; ++c) exact[3 * i + c] = add128(exact[3 * i + c], d[c]);
    for (int c = 0; c < 4; ++c) accum[i].sum[c] = accum[i].comp[c] = 0.0f;
}

/* Adaptive sampling's half film: half_film[i] += fixed(sum.w) - fixed(comp.w),
 * enqueued before film_add_exact, which then empties the chunk film. Same
 * error bits as film_add_exact. */
kernel void film_add_exact_half(global const AccumPixel* accum, uint count, global ulong2* half_film, global uint* error) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint bad = 0;
    ulong2 d = add128(fixed_from_float(accum[i].sum[3], &bad), neg128(fixed_from_float(accum[i].comp[3], &bad)));
    if (bad) {
        atomic_or(error, bad);
        return;
    }
    half_film[i] = add128(half_film[i], d);
}

#endif
