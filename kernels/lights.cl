/* Lights for next-event estimation: one table of every light (emissive
 * triangles, point, spot and directional lights, the environment), picked in
 * proportion to power through an alias table built on the host, or by the
 * light BVH (light_bvh.cl, CLP_LIGHT_BVH; the pick is path.cl's). Kinds a scene
 * does not have are compiled out (CLP_HAS_TRIANGLE_LIGHTS, CLP_HAS_DELTA_LIGHTS,
 * CLP_HAS_ENV, CLP_HAS_ENV_MAP). */
#ifndef CLP_LIGHTS_CL
#define CLP_LIGHTS_CL

#include "common.h"
#include "sampling.cl"
#include "intersect.cl"

/* ---- the environment ---------------------------------------------------- */
/* Equirectangular: u = 0.5 + atan2(x, -z) / 2pi across, v = acos(y) / pi down
 * (row 0 is straight up, the image centre looks along -z), after the
 * environment's rotation about +y. Texels are looked up without filtering, so
 * the sampling pdf is exactly proportional to what is returned. */

typedef struct {
    global const float4* pixels;
    /* luminance x sin(theta), in the layout of CLP_ENV_ROW_CDF (shared_structs.h) */
    global const float* cdf;
} EnvMap;

static inline float3 env_rotate(constant const FrameParams* fp, float3 d, float sign) {
    float c = fp->env_rot_cos, s = fp->env_rot_sin * sign;
    return (float3)(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

#ifdef CLP_HAS_ENV_MAP
static inline uint env_texel(constant const FrameParams* fp, float3 d, float* sin_theta) {
    d = env_rotate(fp, d, 1.0f);
    float u = 0.5f + atan2(d.x, -d.z) * (0.5f * CLP_INV_PI);
    float v = acos(clamp(d.y, -1.0f, 1.0f)) * CLP_INV_PI;
    uint x = min((uint)(u * (float)fp->env_width), fp->env_width - 1);
    uint y = min((uint)(v * (float)fp->env_height), fp->env_height - 1);
    *sin_theta = sqrt(fmax(0.0f, 1.0f - d.y * d.y));
    return y * fp->env_width + x;
}
#endif

/* Radiance arriving along -d from infinitely far. */
static inline float3 env_radiance(constant const FrameParams* fp, const EnvMap* env, float3 d) {
#ifdef CLP_HAS_ENV_MAP
    if (fp->env_width) {
        float st;
        return env->pixels[env_texel(fp, d, &st)].xyz * fp->env_scale;
    }
#endif
    return load3c(fp->env_color);
}

/* Index i with cdf[i] <= u < cdf[i+1] among n intervals (cdf[0] = 0, cdf[n] = 1). */
static inline uint cdf_find(global const float* cdf, uint n, float u) {
    uint lo = 0, hi = n;
    while (hi - lo > 1) {
        uint mid = (lo + hi) / 2;
        if (cdf[mid] <= u) lo = mid; else hi = mid;
    }
    return lo;
}

/* Solid-angle pdf of env_sample_direction choosing d. */
static inline float env_pdf(constant const FrameParams* fp, const EnvMap* env, float3 d) {
#ifdef CLP_HAS_ENV_MAP
    if (fp->env_width && CLP_ENV_IS_SAMPLED(env->cdf[0])) {
        uint w = fp->env_width, h = fp->env_height;
        float st;
        uint i = env_texel(fp, d, &st), x = i % w, y = i / w;
        if (st <= 0.0f) return 0.0f;
        global const float* row = env->cdf + CLP_ENV_ROW_CDF(w, h, y);
        float p_uv = (env->cdf[y + 1] - env->cdf[y]) * (row[x + 1] - row[x]) * (float)w * (float)h;
        return p_uv / (2.0f * CLP_PI * CLP_PI * st);
    }
#endif
    return 0.25f * CLP_INV_PI;
}

/* A direction towards the environment: by the image's luminance (pbrt's
 * piecewise-constant 2D distribution) or, for a constant colour or when not
 * importance sampled (CLP_ENV_NOT_SAMPLED), uniformly on the sphere. */
static inline float3 env_sample_direction(constant const FrameParams* fp, const EnvMap* env, float u1, float u2) {
#ifdef CLP_HAS_ENV_MAP
    if (fp->env_width && CLP_ENV_IS_SAMPLED(env->cdf[0])) {
        uint w = fp->env_width, h = fp->env_height;
        uint y = cdf_find(env->cdf, h, u1);
        float dv = (u1 - env->cdf[y]) / fmax(env->cdf[y + 1] - env->cdf[y], 1e-30f);
        global const float* row = env->cdf + CLP_ENV_ROW_CDF(w, h, y);
        uint x = cdf_find(row, w, u2);
        float du = (u2 - row[x]) / fmax(row[x + 1] - row[x], 1e-30f);
        float u = ((float)x + clamp(du, 0.0f, 1.0f)) / (float)w;
        float v = ((float)y + clamp(dv, 0.0f, 1.0f)) / (float)h;
        /* theta and phi in units of pi (cos_sin_pi: sampling.cl) */
        const float2 theta = cos_sin_pi(v), phi = cos_sin_pi((u - 0.5f) * 2.0f);
        float3 d = (float3)(theta.y * phi.y, theta.x, -theta.y * phi.x);
        return env_rotate(fp, d, -1.0f);
    }
#endif
    float z = 1.0f - 2.0f * u1, r = sqrt(fmax(0.0f, 1.0f - z * z));
    const float2 phi = cos_sin_pi(2.0f * u2); /* the angle in units of pi */
    return (float3)(r * phi.x, z, r * phi.y);
}

/* ---- picking and sampling ----------------------------------------------- */

static inline uint pick_light(global const AliasEntry* alias, uint n, float u) {
    float x = u * (float)n;
    uint i = min((uint)x, n - 1);
    return (x - (float)i) < alias[i].prob ? i : alias[i].alias;
}

typedef struct {
    float3 wi;  /* unit direction towards the light */
    float3 L;   /* radiance (or for delta lights, irradiance-like intensity / r^2) arriving along -wi */
    float pdf;  /* solid-angle pdf including the pick; for delta lights the pick probability alone */
    float3 to;  /* the point sampled on the light (finite lights) */
    int infinite;
    int delta;
} LightSample;

/* Triangle lights are sampled uniformly in the solid angle they subtend at the
 * shading point (Arvo 1995), which removes the 1/r^2 and light-cosine factors
 * from the estimate: what makes area sampling noisy next to a light. Points
 * are sampled uniformly in area instead where that is as good, or the
 * spherical construction is unreliable in float:
 * - the triangle is small for its distance (area below CLP_MIN_SPHERICAL_SPREAD
 *   times the squared distance to the nearest vertex, a test without square
 *   roots): 1/r^2 and the cosines then vary little over it, and solid-angle
 *   sampling's atan2, sin, cos and dozen square roots cost more than the
 *   variance they remove (cornell-classic: the same error with 0.1, in less
 *   time; benchmarks/results/pocl-xeon-2core/kernel-speed);
 * - the triangle subtends very little, or nearly a hemisphere (pbrt-v4's
 *   Triangle::Sample thresholds);
 * - p lies near the triangle's plane (height over the plane below a tenth of
 *   the distance to the nearest vertex): the spherical triangle is then a
 *   sliver along a great circle, and Arvo's formulas cancel badly in float.
 *   Emulated in float32 over random points, its samples failed a chi-square
 *   test against 1/omega below a ratio of 0.021 and passed above it;
 *   tests/kernels/lights_test.cpp checks both sides of the rule.
 * Sampling and pdf use the same rule, so MIS stays exact. The thresholds
 * (CLP_*_SPHERICAL_*) are in shared_structs.h, where the host's tests read them. */

/* The solid angle of light triangle (a, b, c) at p when it is sampled by solid
 * angle, else 0; n is the triangle's unit normal and area2 twice its area.
 * The unit directions towards the vertices go to *ua, *ub, *uc, for the
 * sampling to reuse. */
static inline float triangle_solid_angle_dirs(float3 a, float3 b, float3 c, float3 n, float area2, float3 p, float3* ua,
                                       float3* ub, float3* uc) {
    float3 da = a - p, db = b - p, dc = c - p;
    float d2 = fmin(dot(da, da), fmin(dot(db, db), dot(dc, dc)));
    if (!(0.5f * area2 >= CLP_MIN_SPHERICAL_SPREAD * d2)) return 0.0f;
    float la = length3(da), lb = length3(db), lc = length3(dc);
    if (!(la > 0.0f && lb > 0.0f && lc > 0.0f)) return 0.0f;
    if (!(fabs(dot(n, da)) >= CLP_MIN_SPHERICAL_ELEVATION * fmin(la, fmin(lb, lc)))) return 0.0f;
    *ua = da / la;
    *ub = db / lb;
    *uc = dc / lc;
    float omega = spherical_triangle_area(*ua, *ub, *uc);
    return (omega >= CLP_MIN_SPHERICAL_AREA && omega <= CLP_MAX_SPHERICAL_AREA) ? omega : 0.0f;
}

/* The same, for the pdf of a direction (MIS). */
static inline float triangle_sampled_solid_angle(float3 a, float3 b, float3 c, float3 p) {
    float3 ua, ub, uc, n = cross(b - a, c - a);
    return triangle_solid_angle_dirs(a, b, c, normalize3(n), length3(n), p, &ua, &ub, &uc);
}

/* Solid-angle pdf (without the pick) of sampling, from p, the point at
 * distance dist along unit direction d on triangle light l. */
static inline float triangle_sample_pdf(global const Light* l, float3 p, float3 d, float dist) {
    float3 a = load3g(l->a), b = load3g(l->b), c = load3g(l->c);
    float omega = triangle_sampled_solid_angle(a, b, c, p);
    if (omega > 0.0f) return 1.0f / omega;
    float3 n = cross(b - a, c - a);
    float area2 = length3(n);
    float cos_l = fabs(dot(n, d)) / area2;
    if (!(cos_l > 0.0f)) return 0.0f;
    return dist * dist / (0.5f * area2 * cos_l);
}

/* A point on triangle light l as seen from p (radiance, direction, pdf without
 * the pick, shadow-ray end). Returns 0 when it gives nothing. */
static inline int sample_triangle_light(global const Light* l, float3 p, float u1, float u2, LightSample* s) {
    float3 a = load3g(l->a), b = load3g(l->b), c = load3g(l->c);
    float3 n = cross(b - a, c - a);
    float area2 = length3(n);
    if (!(area2 > 0.0f)) return 0;
    float b0, b1;
    float3 ua, ub, uc;
    float omega = triangle_solid_angle_dirs(a, b, c, normalize3(n), area2, p, &ua, &ub, &uc);
    if (omega > 0.0f) {
        float3 w = sample_spherical_triangle(ua, ub, uc, omega, u1, u2);
        /* Where w meets the triangle's plane, as barycentrics clamped into the
         * triangle (w lies inside it up to rounding). */
        float dn = dot(w, n);
        if (dn == 0.0f) return 0;
        float3 x = p + (dot(a - p, n) / dn) * w;
        float inv = 1.0f / (area2 * area2);
        b1 = fmax(0.0f, dot(cross(x - a, c - a), n) * inv);
        float b2 = fmax(0.0f, dot(cross(b - a, x - a), n) * inv);
        float sum = b1 + b2;
        if (sum > 1.0f) { b1 /= sum; b2 /= sum; }
        b0 = 1.0f - b1 - b2;
    } else {
        /* Uniform in area: barycentrics by the square-root warp (PBR 4th ed., A.5.5). */
        float su = sqrt(u1);
        b0 = 1.0f - su;
        b1 = u2 * su;
    }
    float b2 = 1.0f - b0 - b1;
    float3 q = b0 * a + b1 * b + b2 * c;
    float3 d = q - p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return 0;
    float dist = sqrt(dist2);
    s->wi = d / dist;
    float cos_l = -dot(n, s->wi) / area2;
    if (cos_l <= 0.0f && !(l->flags & CLP_LIGHTF_TWO_SIDED)) return 0;
    cos_l = fabs(cos_l);
    if (cos_l <= 0.0f) return 0;
    s->pdf = omega > 0.0f ? 1.0f / omega : dist2 / (0.5f * area2 * cos_l);
    s->L = load3g(l->L);
    /* The end of the shadow ray moves off the light by its own error bound. */
    float3 err = CLP_GAMMA(10) * (fabs(b0 * a) + fabs(b1 * b) + fabs(b2 * c));
    s->to = offset_ray_origin(q, err, n / area2, -s->wi);
    return 1;
}

/* Samples light li, picked with probability pmf, as seen from p. Returns 0
 * when it gives nothing. */
static inline int sample_light(global const Light* lights, uint li, float pmf, constant const FrameParams* fp,
                               const EnvMap* env, float3 p, float u1, float u2, LightSample* s) {
    global const Light* l = &lights[li];
    s->infinite = 0;
    s->delta = 0;
    switch (l->type) {
#ifdef CLP_HAS_TRIANGLE_LIGHTS
    case CLP_LIGHT_TRIANGLE: {
        if (!sample_triangle_light(l, p, u1, u2, s)) return 0;
        s->pdf *= pmf;
        return 1;
    }
#endif
#ifdef CLP_HAS_DELTA_LIGHTS
    case CLP_LIGHT_POINT:
    case CLP_LIGHT_SPOT: {
        float3 d = load3g(l->a) - p;
        float dist2 = dot(d, d);
        if (!(dist2 > 0.0f)) return 0;
        s->wi = d * rsqrt(dist2);
        float falloff = 1.0f;
        if (l->type == CLP_LIGHT_SPOT)
            falloff = smoothstep(l->cos_outer, l->cos_inner, dot(-s->wi, load3g(l->b)));
        s->L = load3g(l->L) * (falloff / dist2);
        s->pdf = pmf;
        s->to = load3g(l->a);
        s->delta = 1;
        return falloff > 0.0f;
    }
    case CLP_LIGHT_DIRECTIONAL:
        s->wi = -load3g(l->b);
        s->L = load3g(l->L);
        s->pdf = pmf;
        s->infinite = 1;
        s->delta = 1;
        return 1;
#endif
#ifdef CLP_HAS_ENV
    case CLP_LIGHT_ENVIRONMENT:
        s->wi = env_sample_direction(fp, env, u1, u2);
        s->pdf = pmf * env_pdf(fp, env, s->wi);
        s->L = env_radiance(fp, env, s->wi);
        s->infinite = 1;
        return s->pdf > 0.0f;
#endif
    default: return 0;
    }
}

/* Multiple importance sampling, Veach's power heuristic (beta = 2). */
static inline float power_heuristic(float pdf_a, float pdf_b) {
    if (!(pdf_a > 0.0f)) return 0.0f;
    float r = pdf_b / pdf_a; /* as a ratio: squares of large pdfs would overflow */
    return 1.0f / (1.0f + r * r);
}

#endif
