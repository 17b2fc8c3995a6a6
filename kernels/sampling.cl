/* Sampling directions and building frames. */
#ifndef CLP_SAMPLING_CL
#define CLP_SAMPLING_CL

#include "common.h"

#define CLP_PI 3.14159265358979323846f
#define CLP_INV_PI 0.31830988618379067154f

/* Orthonormal basis around a unit vector n, without the singularity of the
 * cross-product method: Duff et al. 2017, "Building an Orthonormal Basis, Revisited". */
static inline void make_frame(float3 n, float3* t, float3* b) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    *t = (float3)(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    *b = (float3)(c, s + n.y * n.y * a, -n.y);
}

/* (cos(pi y), sin(pi y)) for |y| <= 1/4, by polynomials in y^2 fitted on
 * that interval by least squares (degree 8 for cos, 9 for sin). Through
 * cos_sin_pi, at most 2.1 u (u = 2^-24) relative error in float, measured
 * against double in tests/kernels/sampling_test, which holds it to a 20 u
 * first-order bound (OpenCL allows cospi and sinpi 4 ulp). PoCL's
 * cospi and sinpi each reduce an argument of any size and evaluate their own
 * polynomial: this pair made diffuse renders 1.07-1.08x faster on a CPU. */
static inline float2 cos_sin_pi_quarter(float y) {
    const float t = y * y;
    const float c = 1.0f + t * (-4.934802055358887f +
                                t * (4.058712005615234f +
                                     t * (-1.3352620601654053f + t * (0.23530808091163635f + t * -0.025464996695518494f))));
    const float s = y * (3.1415927410125732f +
                         t * (-5.167712688446045f +
                              t * (2.5501620769500732f + t * (-0.5991922616958618f + t * 0.08093539625406265f))));
    return (float2)(c, s);
}

/* (cos(pi x), sin(pi x)) for any finite x: x = k/2 + y with |y| <= 1/4
 * (y exact: Sterbenz), then the quarter turns k. */
static inline float2 cos_sin_pi(float x) {
    const float k = rint(2.0f * x);
    const float2 cs = cos_sin_pi_quarter(x - 0.5f * k);
    const float q = k - 4.0f * floor(0.25f * k); /* k mod 4, exactly */
    const float2 turned = q >= 2.0f ? -cs : cs;  /* half a turn */
    return (q == 1.0f || q == 3.0f) ? (float2)(-turned.y, turned.x) : turned; /* a quarter turn more */
}

/* Uniform point on the unit disk by Shirley & Chiu's (1997) concentric map,
 * which keeps strata compact (less distortion than the polar map). The angle
 * is pi/4 * b/a, or pi/2 - pi/4 * a/b: in units of pi within a quarter of 0
 * and of 1/2, so no reduction by an inexact pi, and one rounding fewer. */
static inline float2 sample_concentric_disk(float u1, float u2) {
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f) return (float2)(0.0f, 0.0f);
    if (fabs(a) > fabs(b)) return a * cos_sin_pi_quarter(0.25f * (b / a));
    const float2 cs = cos_sin_pi_quarter(-0.25f * (a / b)); /* pi/2 + pi y: (-sin, cos) of pi y */
    return b * (float2)(-cs.y, cs.x);
}

/* Cosine-weighted direction about +z (Malley's method: lift a uniform disk
 * point to the hemisphere). pdf = cos(theta) / pi. The height is lifted from
 * the disk radius (|a| or |b| of the concentric map) rather than from the
 * point, whose cos^2 + sin^2 may round a little above 1: near the rim
 * 1 - x^2 - y^2 could then clamp to 0, a direction in the tangent plane whose
 * pdf is 0. */
static inline float3 sample_cosine_hemisphere(float u1, float u2) {
    const float2 d = sample_concentric_disk(u1, u2);
    const float r = fmax(fabs(2.0f * u1 - 1.0f), fabs(2.0f * u2 - 1.0f));
    return (float3)(d.x, d.y, sqrt(fmax(0.0f, 1.0f - r * r)));
}

static inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * CLP_INV_PI : 0.0f; }

/* Uniform direction on the hemisphere about +z. pdf = 1 / (2 pi). */
static inline float3 sample_uniform_hemisphere(float u1, float u2) {
    float z = u1;
    float r = sqrt(fmax(0.0f, 1.0f - z * z));
    const float2 cs = cos_sin_pi(2.0f * u2); /* the angle in units of pi */
    return (float3)(r * cs.x, r * cs.y, z);
}

static inline float uniform_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? 0.5f * CLP_INV_PI : 0.0f; }

/* The direction a diffuse bounce takes about +z, and its pdf: cosine-weighted
 * by default; uniform with -DCLP_UNIFORM_HEMISPHERE (the thesis text's choice,
 * kept so that the convergence benchmark can measure what cosine weighting
 * gains). Sample and pdf are chosen together here, so they cannot disagree. */
static inline float3 sample_diffuse_hemisphere(float u1, float u2) {
#ifdef CLP_UNIFORM_HEMISPHERE
    return sample_uniform_hemisphere(u1, u2);
#else
    return sample_cosine_hemisphere(u1, u2);
#endif
}

static inline float diffuse_hemisphere_pdf(float cos_theta) {
#ifdef CLP_UNIFORM_HEMISPHERE
    return uniform_hemisphere_pdf(cos_theta);
#else
    return cosine_hemisphere_pdf(cos_theta);
#endif
}

static inline float3 to_world(float3 v, float3 n) {
    float3 t, b;
    make_frame(n, &t, &b);
    return v.x * t + v.y * b + v.z * n;
}

/* atan2(y, x) for y >= 0, in [0, pi]; NaN for a NaN operand, 0 for y = x = 0
 * (either zero's sign). PoCL's atan2 handles every quadrant and special value
 * and cost 5 % of a render here. atan(r) = r P(r^2) for r = min/max in [0, 1]:
 * P is the degree-8 Chebyshev fit of atan(sqrt(s))/sqrt(s) on [0, 1] (mpmath
 * chebyfit; its relative error 2.3e-8), evaluated by Horner with fused
 * multiply-adds. Then atan(y/x) = pi/2 - atan(x/y) above the diagonal, and pi
 * minus that for x < 0. tests/kernels/sampling_test.cpp checks the relative
 * error against double precision and derives its bound. */
static inline float atan2_upper(float y, float x) {
    float ax = fabs(x);
    /* Compares, not fmin/fmax, so a NaN operand reaches r. */
    float lo = y < ax ? y : ax, hi = y < ax ? ax : y;
    float r = hi == 0.0f ? 0.0f : lo / hi;
    float s = r * r;
    float p = 0.00276628346f;
    p = fma(p, s, -0.015731249f);
    p = fma(p, s, 0.0421376228f);
    p = fma(p, s, -0.0745685473f);
    p = fma(p, s, 0.106183708f);
    p = fma(p, s, -0.141977981f);
    p = fma(p, s, 0.199918717f);
    p = fma(p, s, -0.333330363f);
    p = fma(p, s, 1.0f);
    float a = r * p;
    a = y > ax ? 0.5f * CLP_PI - a : a;
    return x < 0.0f ? CLP_PI - a : a;
}

/* Solid angle of the spherical triangle of unit vectors a, b, c, by Van
 * Oosterom & Strackee (1983): tan(omega / 2) = |a.(b x c)| / (1 + a.b + b.c + c.a).
 * Unlike the angle-excess formula it does not cancel for small triangles. */
static inline float spherical_triangle_area(float3 a, float3 b, float3 c) {
    return 2.0f * atan2_upper(fabs(dot(a, cross(b, c))), 1.0f + dot(a, b) + dot(b, c) + dot(c, a));
}

/* Unit vector v minus its component along unit vector n, normalised; zero
 * where v is parallel to n (then nothing is added to the component along n). */
static inline float3 orthogonal_part(float3 v, float3 n) {
    float3 w = v - dot(v, n) * n;
    float l = length3(w);
    return l > 0.0f ? w / l : (float3)(0.0f);
}

/* A direction uniform in solid angle over the spherical triangle (a, b, c) of
 * area `area` (unit vectors; area from spherical_triangle_area): Arvo 1995,
 * "Stratified Sampling of Spherical Triangles". u1 picks the sub-triangle
 * (a, b, c') of area u1 * area, u2 the point along the arc from b to c'. */
static inline float3 sample_spherical_triangle(float3 a, float3 b, float3 c, float area, float u1, float u2) {
    /* alpha: the triangle's angle at a, between the great circles ab and ac. */
    float cos_alpha = clamp(dot(normalize3(cross(a, b)), normalize3(cross(a, c))), -1.0f, 1.0f);
    float sin_alpha = sqrt(fmax(0.0f, 1.0f - cos_alpha * cos_alpha));
    float a_hat = u1 * area;
    /* s, t = sin, cos of (a_hat - alpha) by the angle-difference identities,
     * from cos and sin of alpha already at hand (as pbrt-v4's
     * SampleSphericalTriangle does): no acos. (cos_sin_pi rather than sincos,
     * whose private out-argument Oclgrind cannot check.) */
    const float2 cs_a = cos_sin_pi(a_hat * CLP_INV_PI);
    float sin_a = cs_a.y, cos_a = cs_a.x;
    float s = sin_a * cos_alpha - cos_a * sin_alpha, t = cos_a * cos_alpha + sin_a * sin_alpha;
    float u = t - cos_alpha, v = s + sin_alpha * dot(a, b);
    float q = clamp(((v * t - u * s) * cos_alpha - v) / ((v * s + u * t) * sin_alpha), -1.0f, 1.0f);
    float3 c_hat = q * a + sqrt(fmax(0.0f, 1.0f - q * q)) * orthogonal_part(c, a);
    float z = 1.0f - u2 * (1.0f - dot(c_hat, b));
    return z * b + sqrt(fmax(0.0f, 1.0f - z * z)) * orthogonal_part(c_hat, b);
}

#endif
