/* Ray against triangle and box, both exact where it matters:
 *  - triangles: the watertight test of Woop, Benthin and Wald (2013), so no ray
 *    slips between two triangles that share an edge;
 *  - boxes: the slab test, correct for +0 and -0 direction components, with
 *    Ize's (2013) conservative widening so rounding never loses a box;
 *  - secondary-ray origins: offset by the hit point's rounding-error bound
 *    (Pharr, Jakob and Humphreys, PBR 4th ed., 6.8), which works at any scale. */
#ifndef CLP_INTERSECT_CL
#define CLP_INTERSECT_CL

#include "common.h"

/* gamma(n) = n eps / (1 - n eps): the relative error bound of n roundings (PBR 6.8.1). */
#define CLP_GAMMA(n) (((float)(n) * 0x1.0p-24f) / (1.0f - (float)(n) * 0x1.0p-24f))

/* Min and max by compare and select rather than fmin/fmax: the builtins'
 * NaN rules cost a compare and a blend each on x86 (LLVM's minnum). Each
 * returns its second operand when the first is NaN. For scalars and vectors
 * alike (a scalar compare gives 1, a vector one -1: select takes a either way). */
#define CLP_MIN(a, b) select((b), (a), (a) < (b))
#define CLP_MAX(a, b) select((b), (a), (a) > (b))

/* Component k (0, 1 or 2) of v, bit for bit, chosen by masks. On a GPU an
 * indexed private array lives in off-chip local memory, and LLVM turns a
 * chain of compares and selects on k back into a variable index of the
 * vector, which ends there too; masks stay in registers. Once per ray
 * (ray_prepare); the triangle test permutes by permute_axes. CPUs keep the
 * indexed copy (ray_prepare, intersect_triangle), which PoCL does fastest. */
#ifdef CLP_TARGET_GPU
static inline float component3(float3 v, int k) {
    return as_float((as_uint(v.x) & (k == 0 ? ~0u : 0u)) | (as_uint(v.y) & (k == 1 ? ~0u : 0u)) |
                    (as_uint(v.z) & (k == 2 ? ~0u : 0u)));
}
#endif

typedef struct {
    float3 org;
    float3 dir;
    float3 inv_dir; /* 1/dir: +-infinity for +-0 components, as the slab test needs */
    float sx, sy, sz;
    int kx, ky, kz;
#ifdef CLP_TARGET_GPU
    int swap_xy; /* kx and ky are swapped (d[kz] < 0), for permute_axes */
#endif
    /* Every 1/dir component is finite: then (box plane - org) * inv_dir is
     * never 0 * inf, and the slab test's NaN repair can be skipped. */
    int inv_dir_finite;
    /* Bvh4Node128 rows of each axis's near and far planes (lo_x = 0, hi_x = 1,
     * lo_y = 2, ...): lo is entered first where 1/dir >= 0. */
    int near_x, near_y, near_z;
} RayPre;

/* Per ray, once: every division is one vector division, and the axes are
 * picked by indexing a private copy of d rather than by chains of compares
 * and selects (the same correctly rounded quotients as one by one). */
static inline RayPre ray_prepare(float3 o, float3 d) {
    RayPre r;
    r.org = o;
    r.dir = d;
    r.inv_dir = (float3)(1.0f) / d;
    r.inv_dir_finite = !any(isinf(r.inv_dir));
    r.near_x = r.inv_dir.x < 0.0f ? 1 : 0;
    r.near_y = r.inv_dir.y < 0.0f ? 3 : 2;
    r.near_z = r.inv_dir.z < 0.0f ? 5 : 4;
    float3 a = fabs(d);
    /* kz: the dominant axis; kx, ky follow it cyclically, swapped when d[kz] < 0
     * so that the sheared triangle keeps its winding (Woop et al., section 3). */
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
#ifdef CLP_TARGET_GPU
    float dz = component3(d, kz);
#else
    float da[3];
    vstore3(d, 0, da);
    float dz = da[kz];
#endif
#ifdef CLP_TARGET_GPU
    r.swap_xy = dz < 0.0f;
#endif
    if (dz < 0.0f) {
        int t = kx;
        kx = ky;
        ky = t;
    }
    r.kx = kx;
    r.ky = ky;
    r.kz = kz;
#ifdef CLP_TARGET_GPU
    float3 s = (float3)(component3(d, kx), component3(d, ky), 1.0f) / dz;
#else
    float3 s = (float3)(da[kx], da[ky], 1.0f) / dz;
#endif
    r.sx = s.x;
    r.sy = s.y;
    r.sz = s.z;
    return r;
}

/* For a hit nearer than t's error bound: is the ray's origin in front of the
 * triangle's plane beyond rounding, and heading towards it? Then the ray truly
 * crosses the plane at t > 0, and the watertight edge test (exact signs) has
 * already said the crossing is inside the triangle. The signed distance
 * n.(o - v0) is computed in world space with n = (v1 - v0) x (v2 - v0); its
 * error is at most gamma(8) sum_i |n|_i |o - v0|_i, where |n|_i sums the
 * absolute products of n_i's cross product (one rounding for each edge
 * difference, two for each product and difference, one for o - v0, two for
 * the dot's products and sums: gamma(8); gamma(10) also covers the
 * rounding of the bound itself): a few ulps of |o - v0|, not of the triangle's
 * extent in the sheared frame. */
static inline int origin_clearly_in_front(const RayPre* r, float3 v0, float3 v1, float3 v2) {
#pragma OPENCL FP_CONTRACT OFF
    float3 e1 = v1 - v0, e2 = v2 - v0, w = r->org - v0;
    float3 n = (float3)(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    float3 na = (float3)(fabs(e1.y * e2.z) + fabs(e1.z * e2.y), fabs(e1.z * e2.x) + fabs(e1.x * e2.z),
                         fabs(e1.x * e2.y) + fabs(e1.y * e2.x));
    float dist = n.x * w.x + n.y * w.y + n.z * w.z;
    float bound = CLP_GAMMA(10) * (na.x * fabs(w.x) + na.y * fabs(w.y) + na.z * fabs(w.z));
    float towards = n.x * r->dir.x + n.y * r->dir.y + n.z * r->dir.z;
    return fabs(dist) > bound && ((dist > 0.0f && towards < 0.0f) || (dist < 0.0f && towards > 0.0f));
}

#ifdef CLP_TARGET_GPU
/* v's components in the order kx, ky, kz: a rotation that brings kz last
 * (kx and ky follow it cyclically), then kx and ky swapped where the ray
 * says so. Selects on three conditions the walk keeps as predicates: by
 * component3 on kx, ky and kz, the nine masks were hoisted out of the walk
 * into nine registers, and the traversal and wavefront trace kernels took
 * 4-8 registers more at sm_90 (59 instead of 64 for batch_trace_closest, 64
 * instead of 72 for an alpha-masked scene's shadow walk). The same values. */
static inline float3 permute_axes(const RayPre* r, float3 v) {
    const float3 c = r->kz == 0 ? v.yzx : (r->kz == 1 ? v.zxy : v);
    return r->swap_xy ? c.yxz : c;
}
#endif

/* Watertight ray/triangle test. On a hit in (0, tmax) returns 1 and writes t and
 * the barycentric weights (b1, b2) of v1 and v2. */
__attribute__((always_inline)) static inline int intersect_triangle(const RayPre* r, float3 v0, float3 v1, float3 v2,
                                                                    float tmax, float* t_out, float* b1_out,
                                                                    float* b2_out) {
    /* Fused multiply-adds would round the two triangles sharing an edge
     * differently, and a ray could then miss both (Woop et al., section 4). */
#pragma OPENCL FP_CONTRACT OFF
    /* v - o, then permuted: the same values as permuting both first
     * (subtraction is per component). The permutation is an indexed read of
     * a private array, a store and three loads, where picking each component
     * by comparing k took two compares and two selects. */
#ifdef CLP_TARGET_GPU
    const float3 A = permute_axes(r, v0 - r->org), B = permute_axes(r, v1 - r->org), C = permute_axes(r, v2 - r->org);
#else
    float va[3], vb[3], vc[3];
    vstore3(v0 - r->org, 0, va);
    vstore3(v1 - r->org, 0, vb);
    vstore3(v2 - r->org, 0, vc);
    float3 A = (float3)(va[r->kx], va[r->ky], va[r->kz]);
    float3 B = (float3)(vb[r->kx], vb[r->ky], vb[r->kz]);
    float3 C = (float3)(vc[r->kx], vc[r->ky], vc[r->kz]);
#endif
    float sxaz = r->sx * A.z, syaz = r->sy * A.z;
    float sxbz = r->sx * B.z, sybz = r->sy * B.z;
    float sxcz = r->sx * C.z, sycz = r->sy * C.z;
    float Ax = A.x - sxaz, Ay = A.y - syaz;
    float Bx = B.x - sxbz, By = B.y - sybz;
    float Cx = C.x - sxcz, Cy = C.y - sycz;
    float u0 = Cx * By, u1 = Cy * Bx;
    float v0p = Ax * Cy, v1p = Ay * Cx;
    float w0 = Bx * Ay, w1 = By * Ax;
    float U = u0 - u1, V = v0p - v1p, W = w0 - w1;
    /* An edge function of exactly 0 counts as inside, from either side: a ray
     * through a shared edge then hits both triangles rather than neither. */
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = U + V + W;
    if (det == 0.0f) return 0; /* ray in the triangle's plane, or a degenerate triangle */
    float Az = r->sz * A.z, Bz = r->sz * B.z, Cz = r->sz * C.z;
    float T = U * Az + V * Bz + W * Cz;
    /* Compare T with t * det without dividing, keeping the sign of det. */
    if (det < 0.0f) {
        T = -T;
        det = -det;
        U = -U;
        V = -V;
        W = -W;
    }
    if (T <= 0.0f || T >= tmax * det) return 0;
    float inv = 1.0f / det;
    float t = T * inv;
    /* t must be positive beyond its own rounding error, or a ray leaving a
     * surface just above it can re-hit it, or a coplanar neighbour, "behind"
     * its origin (PBR 4th ed., 6.8.7; one extra gamma(2) for OpenCL's 2.5-ulp
     * division and the scaling by sz). That bound is proportional to the
     * triangle's extent, not to t: alone, it also rejected true hits within
     * ~1e-5 of a triangle's size, and rays from a floor next to a wall (a
     * concave corner) or across a thin gap passed through (tests/robustness/
     * scale_test). For sliver triangles seen nearly edge-on it even exceeds t
     * itself (it grows like t^2 over the triangle's area seen along the ray):
     * primary rays went through a 4M-triangle sphere (tests/kernels/
     * intersect_test, TinyGrazingTrianglesFarAwayAreHit). A hit within the
     * bound is therefore kept when the origin's distance to the plane, whose
     * bound is tight, shows it clearly in front. */
    /* None of these is NaN (finite vertices, a finite nonzero det), so
     * CLP_MAX gives fmax's result without paying for its NaN rule. */
    float max_z = CLP_MAX(fabs(Az), CLP_MAX(fabs(Bz), fabs(Cz)));
    float max_x = CLP_MAX(fabs(Ax), CLP_MAX(fabs(Bx), fabs(Cx)));
    float max_y = CLP_MAX(fabs(Ay), CLP_MAX(fabs(By), fabs(Cy)));
    float delta_z = CLP_GAMMA(5) * max_z;
    float delta_x = CLP_GAMMA(7) * (max_x + max_z), delta_y = CLP_GAMMA(7) * (max_y + max_z);
    float delta_e = 2.0f * (CLP_GAMMA(4) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    float max_e = CLP_MAX(fabs(U), CLP_MAX(fabs(V), fabs(W)));
    float delta_t = 3.0f * (CLP_GAMMA(5) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv;
    if (t <= delta_t && !origin_clearly_in_front(r, v0, v1, v2)) return 0;
    *t_out = t;
    *b1_out = V * inv;
    *b2_out = W * inv;
    return 1;
}

/* Slab test of one box. A zero direction component gives an infinite 1/d;
 * for an origin exactly on that slab's plane the product 0 * inf is NaN. Such
 * a ray lies in the box's face, and a closed box contains it: the NaN is
 * replaced by the infinity of the opposite sign to the other plane's
 * distance, which makes that axis's interval (-inf, inf), whatever the sign
 * of the zero. (Without this, rays in a coordinate plane through a vertex leak
 * between the boxes on both sides of the plane.)
 * Returns the entry distance, or +INFINITY for a miss. */
static inline float intersect_box(const RayPre* r, float3 lo, float3 hi, float tmax) {
    float3 t0 = (lo - r->org) * r->inv_dir;
    float3 t1 = (hi - r->org) * r->inv_dir;
    t0 = select(t0, -t1, isnan(t0));
    t1 = select(t1, -t0, isnan(t1));
    /* fmin/fmax drop a NaN that remains (a flat box with the origin in it): that axis then bounds nothing. */
    float3 tn = fmin(t0, t1), tf = fmax(t0, t1);
    float tnear = fmax(fmax(tn.x, tn.y), fmax(tn.z, 0.0f));
    /* Ize (2013), "Robust BVH Ray Traversal": widen the exit distance by the
     * rounding of the subtraction, the product and the (not correctly rounded,
     * 2.5 ulp in OpenCL) reciprocal, so a ray never misses a box it enters. */
    float tfar = fmin(fmin(tf.x, tf.y), fmin(tf.z, tmax)) * (1.0f + 2.0f * CLP_GAMMA(5));
    return tnear <= tfar ? tnear : INFINITY;
}

/* The entry distance of four boxes from each axis's near and far slab
 * distances, or +INFINITY for a miss: the exit distance is widened by the
 * rounding of the subtraction, the product and the reciprocal (Ize 2013, as
 * intersect_box). An axis whose near and far are NaN (a flat box with the
 * origin in it, see intersect_box4) stands first against a partial result
 * that is never NaN (the chains start from 0 and tmax), so it bounds nothing,
 * as with fmin/fmax. */
static inline float4 slab_entry4(float4 nx, float4 ny, float4 nz, float4 fx, float4 fy, float4 fz, float tmax) {
    float4 tnear = CLP_MAX(nx, CLP_MAX(ny, CLP_MAX(nz, (float4)(0.0f))));
    float4 tfar = CLP_MIN(fx, CLP_MIN(fy, CLP_MIN(fz, (float4)(tmax)))) * (1.0f + 2.0f * CLP_GAMMA(5));
    return select((float4)(INFINITY), tnear, tnear <= tfar);
}

/* intersect_box for the four child boxes of a Bvh4Node128 at once, stored by
 * coordinate: lane by lane the same slab distances, the same NaN repair and
 * the same conservative widening, so the same boxes are entered at the same
 * distances. */
static inline float4 intersect_box4(const RayPre* r, float4 lo_x, float4 hi_x, float4 lo_y, float4 hi_y, float4 lo_z,
                             float4 hi_z, float tmax) {
    float4 t0x = (lo_x - r->org.x) * r->inv_dir.x, t1x = (hi_x - r->org.x) * r->inv_dir.x;
    float4 t0y = (lo_y - r->org.y) * r->inv_dir.y, t1y = (hi_y - r->org.y) * r->inv_dir.y;
    float4 t0z = (lo_z - r->org.z) * r->inv_dir.z, t1z = (hi_z - r->org.z) * r->inv_dir.z;
    /* The box planes and the origin are finite, so a NaN here is 0 * inf:
     * none for a ray whose 1/dir is finite (nearly every ray; the branch
     * follows the ray, so it is predicted). */
    if (!r->inv_dir_finite) {
        t0x = select(t0x, -t1x, isnan(t0x));
        t1x = select(t1x, -t0x, isnan(t1x));
        t0y = select(t0y, -t1y, isnan(t0y));
        t1y = select(t1y, -t0y, isnan(t1y));
        t0z = select(t0z, -t1z, isnan(t0z));
        t1z = select(t1z, -t0z, isnan(t1z));
    }
    /* A NaN left after the repair (flat box, origin in it) is in both t0 and
     * t1 of its axis, so its near and far are NaN. */
    return slab_entry4(CLP_MIN(t0x, t1x), CLP_MIN(t0y, t1y), CLP_MIN(t0z, t1z), CLP_MAX(t0x, t1x),
                       CLP_MAX(t0y, t1y), CLP_MAX(t0z, t1z), tmax);
}

/* What the 4-box test reads of the ray at every node, copied out of RayPre
 * once per traversal (ray_box4): read through the RayPre pointer, it was
 * loaded again at every node, as the compiler cannot tell that the
 * traversal's stores to its stack leave it alone. Origin and 1/dir are
 * broadcast; near_x... are RayPre's plane rows. */
typedef struct {
    float4 ox, oy, oz;
    float4 ix, iy, iz;
    int near_x, near_y, near_z;
} RayBox4;

static inline RayBox4 ray_box4(const RayPre* r) {
    RayBox4 b;
    b.ox = (float4)(r->org.x);
    b.oy = (float4)(r->org.y);
    b.oz = (float4)(r->org.z);
    b.ix = (float4)(r->inv_dir.x);
    b.iy = (float4)(r->inv_dir.y);
    b.iz = (float4)(r->inv_dir.z);
    b.near_x = r->near_x;
    b.near_y = r->near_y;
    b.near_z = r->near_z;
    return b;
}

/* intersect_box4 for a ray whose 1/dir is finite, over the node rows n (a
 * Bvh4Node128), each axis's planes read in the order the ray crosses them. For
 * such a ray the slab distances are finite, and (near - o) / d <= (far - o) / d
 * also after rounding (rounding is monotonic), so the per-axis min and max of
 * intersect_box4 are known in advance: the same distances, bit for bit, with
 * twelve compares and selects fewer. */
static inline float4 intersect_box4_ordered(const RayBox4* b, global const float4* n, float tmax) {
#ifdef CLP_TARGET_GPU
    /* The plane rows again from the signs of 1/dir at each node, as ray_prepare
     * made them: three registers fewer through the walk for two compares
     * each, and the instanced walk's wf_trace came within its 64 registers
     * at sm_90 (67 with the rows kept). */
    const int near_x = b->ix.s0 < 0.0f ? 1 : 0, near_y = b->iy.s0 < 0.0f ? 3 : 2, near_z = b->iz.s0 < 0.0f ? 5 : 4;
#else
    const int near_x = b->near_x, near_y = b->near_y, near_z = b->near_z;
#endif
    return slab_entry4((n[near_x] - b->ox) * b->ix, (n[near_y] - b->oy) * b->iy, (n[near_z] - b->oz) * b->iz,
                       (n[near_x ^ 1] - b->ox) * b->ix, (n[near_y ^ 1] - b->oy) * b->iy,
                       (n[near_z ^ 1] - b->oz) * b->iz, tmax);
}

/* Hit point from barycentrics, with a bound on its distance from the exact
 * point v0 + b1 (v1 - v0) + b2 (v2 - v0), which lies in the triangle's plane
 * for any b1, b2 (so the barycentrics' own rounding only slides it within the
 * plane). pbrt's form b0 v0 + b1 v1 + b2 v2 with its bound gamma(7)
 * sum |b_i v_i| (PBR 4th ed., 6.8.5) is some ten ulps of |p| on every axis:
 * 0.6 units at 10^6, and bounce rays that started that far off the surface
 * saw a room shrunk by it, its darker corners under-sampled (the image came
 * out 0.4 % brighter at 10^6, 1.7 % at 4 10^6; docs/robustness.md). Here the
 * small part b1 e1 + b2 e2 is bounded relative to the triangle's extent
 * (gamma(3) for the edge difference, the product and the sum; gamma(6) also
 * covers the bound's own roundings), and the rounding of the final addition
 * to v0 is not bounded but computed exactly by TwoSum (Knuth, TAOCP vol. 2,
 * 4.2.2; exact for correctly rounded addition, which OpenCL guarantees, and
 * without contraction). On an axis-aligned face both vanish along its
 * normal, and the point is exactly in the plane; elsewhere the bound is at
 * most half an ulp of |p| more than the triangle's own rounding. */
static inline float3 hit_point(float3 v0, float3 v1, float3 v2, float b1, float b2, float3* err) {
#pragma OPENCL FP_CONTRACT OFF
    float3 e1 = v1 - v0, e2 = v2 - v0;
    float3 b1e1 = b1 * e1, b2e2 = b2 * e2;
    float3 s = b1e1 + b2e2;
    float3 p = v0 + s;
    float3 sv = p - s;
    float3 rounding = (v0 - sv) + (s - (p - sv)); /* exactly (v0 + s) - p */
    /* (1 + gamma(4)) |rounding|, itself rounded, is still at least (1 + 2u)
     * |rounding|, and so is the first term: their float sum is an upper bound. */
    *err = CLP_GAMMA(6) * (fabs(b1e1) + fabs(b2e2)) + (1.0f + CLP_GAMMA(4)) * fabs(rounding);
    return p;
}

static inline float next_float_away(float x, float dir_sign) {
    return dir_sign > 0.0f ? nextafter(x, INFINITY) : (dir_sign < 0.0f ? nextafter(x, -INFINITY) : x);
}

/* Origin for a ray leaving a surface at p towards w: moved along the normal
 * past the error box around p, then rounded away from the surface, so that the
 * new ray cannot re-hit the surface it left, at any scale (PBR 4th ed., 6.8.6). */
static inline float3 offset_ray_origin(float3 p, float3 err, float3 n, float3 w) {
    float d = dot(fabs(n), err);
    float3 offset = d * n;
    if (dot(w, n) < 0.0f) offset = -offset;
    float3 po = p + offset;
    return (float3)(next_float_away(po.x, offset.x), next_float_away(po.y, offset.y),
                    next_float_away(po.z, offset.z));
}

#undef CLP_MIN
#undef CLP_MAX

#endif
