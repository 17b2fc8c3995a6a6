/* What every kernel file needs: the layouts shared with the host, the loads
 * that turn their float[3] fields into float3 (shared structs hold no float3,
 * see shared_structs.h), and how functions are inlined.
 *
 * Every function is static: a plain (C99) inline function has no body where
 * a compiler chooses not to inline it, and clang for NVIDIA and AMD GPUs then
 * leaves an unresolved symbol (benchmarks/results/gpu-compile/). Where a
 * function is inlined is decided per device kind (CLP_TARGET_GPU: programs built
 * for GPU devices, render/kernel_programs.hpp):
 *   CLP_WALK            a traversal walk. On a GPU forced inline: a call passes
 *                       the ray through the GPU's stack (the flat walk, called
 *                       twice, took 112 bytes of it). On a CPU out of line: PoCL
 *                       runs a kernel as a loop over work-items, and with the
 *                       walk inlined into it bunny's ray batches ran 1.08-1.28x
 *                       slower (bench rays --ab-kernels, paired, 2-core EPYC).
 *   CLP_GPU_INLINE      forced inline on a GPU (what a GPU keeps out of line
 *                       it hands arguments through its stack), left to the
 *                       compiler on a CPU. */
#ifndef CLP_COMMON_H
#define CLP_COMMON_H

#include "shared_structs.h"

#ifdef CLP_TARGET_GPU
#define CLP_WALK __attribute__((always_inline)) static inline
#define CLP_GPU_INLINE __attribute__((always_inline)) static inline
#else
#define CLP_WALK __attribute__((noinline)) static
#define CLP_GPU_INLINE static inline
#endif

static inline float3 load3(const float* p) { return (float3)(p[0], p[1], p[2]); }
static inline float3 load3g(global const float* p) { return (float3)(p[0], p[1], p[2]); }
static inline float3 load3c(constant const float* p) { return (float3)(p[0], p[1], p[2]); }

/* length and normalize without the builtins' guard against the overflow and
 * underflow of dot(v, v) where it is a normal float: PoCL's builtins rescale v
 * speculatively, which cost 3 % of a render (bench render-ab). There the same
 * formula as PoCL's, so the same bits (tests/kernels/common_test.cpp; the
 * bundled scenes rendered bit for bit as before). Elsewhere (a vector longer than
 * 1.8e19 or shorter than 1.1e-19, or not finite) the builtins answer, so scenes
 * at any scale keep their lights and normals. */
/* Out of line, so that the compiler keeps the test a branch rather than
 * computing the builtin beside the fast result and selecting. */
__attribute__((noinline)) static float length_builtin(float3 v) { return length(v); }
__attribute__((noinline)) static float3 normalize_builtin(float3 v) { return normalize(v); }
static inline float length3(float3 v) {
    float d = dot(v, v);
    if (d >= FLT_MIN && d < INFINITY) return sqrt(d);
    return length_builtin(v);
}
static inline float3 normalize3(float3 v) {
    float d = dot(v, v);
    if (d >= FLT_MIN && d < INFINITY) return v * rsqrt(d);
    return normalize_builtin(v);
}

#endif
