/* Random numbers: one xorshift32 stream per (pixel, sample), seeded by hashing
 * (seed, pixel, sample index). Hashing rather than offsetting makes streams of
 * neighbouring pixels and successive samples independent; a stream's state is
 * never zero (xorshift's one fixed point). */
#ifndef CLP_RNG_CL
#define CLP_RNG_CL

/* Plain C over shared_structs.h's types: the host's CPU path tracer
 * (host/bench/cpu_estimator.hpp) includes this file too, so the streams have
 * one definition. */
#include "shared_structs.h"

/* "lowbias32" from C. Wellons' hash prospector (2018): a bijective 32-bit mixer
 * with very low avalanche bias; bijective, so distinct inputs never collide. */
static inline uint hash_u32(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

typedef struct {
    uint state;
} Rng;

static inline Rng rng_seed(uint pixel, uint sample, uint seed) {
    uint h = hash_u32(hash_u32(hash_u32(seed ^ 0x6a09e667u) ^ pixel) ^ sample);
    Rng r;
    r.state = h ? h : 0x9e3779b9u;
    return r;
}

/* Marsaglia (2003), xorshift32 with shifts (13, 17, 5): period 2^32 - 1. */
static inline uint rng_next_u32(Rng* r) {
    uint x = r->state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    r->state = x;
    return x;
}

/* Uniform in [0, 1): the top 24 bits, so every value is exactly representable. */
static inline float rng_next(Rng* r) { return (float)(rng_next_u32(r) >> 8) * 0x1.0p-24f; }

#endif
