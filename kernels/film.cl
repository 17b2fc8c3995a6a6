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

#endif
