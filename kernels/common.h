/* What every kernel file needs: the layouts shared with the host, and the
 * loads that turn their float[3] fields into float3 (shared structs hold no
 * float3, see shared_structs.h). */
#ifndef CLP_COMMON_H
#define CLP_COMMON_H

#include "shared_structs.h"

inline float3 load3(const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3g(global const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3c(constant const float* p) { return (float3)(p[0], p[1], p[2]); }

/* length and normalize without the builtins' guard against the overflow and
 * underflow of dot(v, v) where it is a normal float: PoCL's builtins rescale v
 * speculatively, which cost 3 % of a render (bench render-ab). There the same
 * formula as PoCL's, so the same bits (tests/kernels/common_test.cpp; the
 * bundled scenes rendered bit for bit as before). Elsewhere (a vector longer than
 * 1.8e19 or shorter than 1.1e-19, or not finite) the builtins answer, so scenes
 * at any scale keep their lights and normals. */
/* Out of line, so that the compiler keeps the test a branch rather than
 * computing the builtin beside the fast result and selecting. */
__attribute__((noinline)) float length_builtin(float3 v) { return length(v); }
__attribute__((noinline)) float3 normalize_builtin(float3 v) { return normalize(v); }
inline float length3(float3 v) {
    float d = dot(v, v);
    if (d >= FLT_MIN && d < INFINITY) return sqrt(d);
    return length_builtin(v);
}
inline float3 normalize3(float3 v) {
    float d = dot(v, v);
    if (d >= FLT_MIN && d < INFINITY) return v * rsqrt(d);
    return normalize_builtin(v);
}

#endif
