/* Picking a light by its estimated contribution at the shading point: the
 * light BVH (Conty Estevez and Kulla 2018; pbrt-v4's BVHLightSampler), built
 * on the host (host/render/light_bvh.*, whose float32 reference this follows
 * operation for operation; docs/light-bvh.md). One u, one root-to-leaf path,
 * no stack. Compiled in with CLP_LIGHT_BVH: path.cl picks next-event
 * estimation's light here and weighs BSDF samples that hit a light by its pmf. */
#ifndef CLP_LIGHT_BVH_CL
#define CLP_LIGHT_BVH_CL

#include "common.h"

typedef struct {
    global const LightBvhNode* nodes;
    global const uint2* trail;      /* per light: its bit trail (lo, hi), 0 when not in the tree */
    global const uint* infinite;    /* the infinite lights, picked uniformly */
    float3 origin, scale;           /* world = origin + q * scale */
    uint node_count, infinite_count;
} LightBvhData;

static inline float lbvh_cos_sub(float sa, float ca, float sb, float cb) { return ca > cb ? 1.0f : ca * cb + sa * sb; }
static inline float lbvh_sin_sub(float sa, float ca, float sb, float cb) { return ca > cb ? 0.0f : sa * cb - ca * sb; }
static inline float lbvh_sqrt0(float x) { return sqrt(fmax(0.0f, x)); }

static inline float3 lbvh_octahedral(uint e) {
    float x = (float)(e & 0xffffu) / 65535.0f * 2.0f - 1.0f, y = (float)(e >> 16) / 65535.0f * 2.0f - 1.0f;
    float z = 1.0f - fabs(x) - fabs(y);
    if (z < 0.0f) {
        float ox = x;
        x = (1.0f - fabs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        y = (1.0f - fabs(ox)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    return normalize((float3)(x, y, z));
}

/* A unit normal as 16 + 16 bits, octahedral (Cigolle et al. 2014, "A survey
 * of efficient representations for independent unit vectors"), rounded to
 * nearest; lbvh_octahedral decodes it. The path keeps the normal it picked a
 * light with in these 32 bits and decodes it again for that light's MIS
 * weight, so both see the same normal to the bit. */
static inline uint lbvh_encode_normal(float3 n) {
    float s = fabs(n.x) + fabs(n.y) + fabs(n.z);
    if (!(s > 0.0f)) return 0x80008000u; /* about +z */
    float x = n.x / s, y = n.y / s;
    if (n.z < 0.0f) {
        float ox = x;
        x = (1.0f - fabs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        y = (1.0f - fabs(ox)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    uint qx = (uint)rint(clamp(x * 0.5f + 0.5f, 0.0f, 1.0f) * 65535.0f);
    uint qy = (uint)rint(clamp(y * 0.5f + 0.5f, 0.0f, 1.0f) * 65535.0f);
    return qx | qy << 16;
}

/* pbrt-v4's LightBounds::Importance of node at p (normal n, or 0). */
static inline float lbvh_importance(const LightBvhData* t, uint node, float3 p, float3 n) {
    global const LightBvhNode* nd = &t->nodes[node];
    float3 qlo = (float3)((float)(nd->qbounds[0] & 0xffffu), (float)(nd->qbounds[1] & 0xffffu),
                          (float)(nd->qbounds[2] & 0xffffu));
    float3 qhi = (float3)((float)(nd->qbounds[0] >> 16), (float)(nd->qbounds[1] >> 16), (float)(nd->qbounds[2] >> 16));
    float3 lo = t->origin + qlo * t->scale, hi = t->origin + qhi * t->scale;
    float3 pc = 0.5f * (lo + hi), diag = hi - lo, d = p - pc;
    float dist2 = dot(d, d);
    float d2 = fmax(dist2, 0.5f * length(diag));
    float3 wi = dist2 > 0.0f ? d / sqrt(dist2) : (float3)(0.0f, 0.0f, 1.0f);
    float cos_w = dot(lbvh_octahedral(nd->axis), wi);
    if (nd->cones & CLP_LIGHT_BVH_TWO_SIDED) cos_w = fabs(cos_w);
    float sin_w = lbvh_sqrt0(1.0f - cos_w * cos_w);
    float r2 = 0.25f * dot(diag, diag);
    float cos_b = dist2 < r2 ? -1.0f : lbvh_sqrt0(1.0f - r2 / dist2);
    float sin_b = lbvh_sqrt0(1.0f - cos_b * cos_b);
    float cos_o = (float)(nd->cones & 0x7fffu) / 32767.0f * 2.0f - 1.0f;
    float cos_e = (float)((nd->cones >> 15) & 0x7fffu) / 32767.0f * 2.0f - 1.0f;
    float sin_o = lbvh_sqrt0(1.0f - cos_o * cos_o);
    float cos_x = lbvh_cos_sub(sin_w, cos_w, sin_o, cos_o);
    float sin_x = lbvh_sin_sub(sin_w, cos_w, sin_o, cos_o);
    float cos_p = lbvh_cos_sub(sin_x, cos_x, sin_b, cos_b);
    if (cos_p <= cos_e) return 0.0f;
    float importance = nd->power * cos_p / d2;
    if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
        float cos_i = fabs(dot(wi, n));
        importance *= lbvh_cos_sub(lbvh_sqrt0(1.0f - cos_i * cos_i), cos_i, sin_b, cos_b);
    }
    return fmax(importance, 0.0f);
}

static inline float lbvh_p_infinite(const LightBvhData* t) {
    float ni = (float)t->infinite_count;
    return ni / (ni + (t->node_count ? 1.0f : 0.0f));
}

/* Picks a light for p, n from u in [0, 1): its index, and its pmf in *pmf;
 * CLP_NO_LIGHT when nothing the descent reaches gives light at p. */
static inline uint light_bvh_sample(const LightBvhData* t, float3 p, float3 n, float u, float* pmf) {
    const float one_minus_eps = 0x1.fffffep-1f;
    float pi = lbvh_p_infinite(t);
    if (t->infinite_count) {
        if (u < pi) {
            float v = fmin(u / pi, one_minus_eps);
            *pmf = pi / (float)t->infinite_count;
            return t->infinite[min((uint)(v * (float)t->infinite_count), t->infinite_count - 1u)];
        }
        if (!t->node_count) return CLP_NO_LIGHT;
        u = fmin((u - pi) / (1.0f - pi), one_minus_eps);
    }
    if (!t->node_count) return CLP_NO_LIGHT;
    float w = 1.0f - pi;
    uint i = 0;
    while (!(t->nodes[i].flags & CLP_LIGHT_BVH_LEAF)) {
        uint c0 = i + 1u, c1 = t->nodes[i].child;
        float i0 = lbvh_importance(t, c0, p, n), i1 = lbvh_importance(t, c1, p, n);
        if (i0 == 0.0f && i1 == 0.0f) return CLP_NO_LIGHT;
        float p0 = i0 / (i0 + i1), p1 = i1 / (i0 + i1);
        if (u < p0) {
            w *= p0;
            u = fmin(u / p0, one_minus_eps);
            i = c0;
        } else {
            w *= p1;
            u = fmin((u - p0) / (1.0f - p0), one_minus_eps);
            i = c1;
        }
    }
    if (i == 0u && !(lbvh_importance(t, 0u, p, n) > 0.0f)) return CLP_NO_LIGHT;
    *pmf = w;
    return t->nodes[i].child;
}

/* The probability that light_bvh_sample picks light li at p, n, along its
 * bit trail. is_infinite: li is one of t->infinite. */
static inline float light_bvh_pmf(const LightBvhData* t, float3 p, float3 n, uint li, int is_infinite) {
    float pi = lbvh_p_infinite(t);
    if (is_infinite) return pi / (float)t->infinite_count;
    uint2 trail = t->trail[li];
    if (trail.x == 0u && trail.y == 0u) return 0.0f;
    float w = 1.0f - pi;
    uint i = 0;
    while (!(t->nodes[i].flags & CLP_LIGHT_BVH_LEAF)) {
        uint c0 = i + 1u, c1 = t->nodes[i].child;
        float i0 = lbvh_importance(t, c0, p, n), i1 = lbvh_importance(t, c1, p, n);
        if (i0 == 0.0f && i1 == 0.0f) return 0.0f;
        if (trail.x & 1u) {
            w *= i1 / (i0 + i1);
            i = c1;
        } else {
            w *= i0 / (i0 + i1);
            i = c0;
        }
        trail.x = (trail.x >> 1) | (trail.y << 31);
        trail.y >>= 1;
    }
    if (i == 0u && !(lbvh_importance(t, 0u, p, n) > 0.0f)) return 0.0f;
    return w;
}

#endif
