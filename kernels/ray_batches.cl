/* The ray-batch benchmark (clpath bench rays, host/bench/ray_batches.cpp):
 * kernels that make the rays (not timed) and kernels that trace a batch
 * (timed), one ray per work-item, through the same walk (traverse_bvh:
 * traverse.cl) the integrator uses (the BVH, the flat list with
 * -DCLP_ACCEL_FLAT, or the two-level BVH of an instanced scene with
 * -DCLP_HAS_INSTANCES). */
#ifndef CLP_RAY_BATCHES_CL
#define CLP_RAY_BATCHES_CL

#include "common.h"
#include "rng.cl"
#include "sampling.cl"
#include "camera.cl"
#include "intersect.cl"
#include "traverse.cl"

/* Primary ray i: tile, then pixel in the tile, then sample in the pixel, so
 * neighbouring work-items trace neighbouring rays. width and height are
 * multiples of CLP_BATCH_TILE (the host checks). */
kernel void batch_primary_rays(constant const CameraData* cam, global BatchRay* out) {
    uint i = get_global_id(0);
    uint spp = CLP_BATCH_GRID * CLP_BATCH_GRID, tile_px = CLP_BATCH_TILE * CLP_BATCH_TILE;
    uint count = cam->width * cam->height * spp;
    if (i >= count) return;
    uint s = i % spp, p = (i / spp) % tile_px, tile = i / (spp * tile_px);
    uint tiles_x = cam->width / CLP_BATCH_TILE;
    uint px = (tile % tiles_x) * CLP_BATCH_TILE + p % CLP_BATCH_TILE;
    uint py = (tile / tiles_x) * CLP_BATCH_TILE + p / CLP_BATCH_TILE;
    float jx = ((float)(s % CLP_BATCH_GRID) + 0.5f) / (float)CLP_BATCH_GRID;
    float jy = ((float)(s / CLP_BATCH_GRID) + 0.5f) / (float)CLP_BATCH_GRID;
    Ray r = camera_ray(cam, px, py, jx, jy);
    global BatchRay* o = &out[i];
    o->o[0] = r.o.x, o->o[1] = r.o.y, o->o[2] = r.o.z;
    o->d[0] = r.d.x, o->d[1] = r.d.y, o->d[2] = r.d.z;
    o->tmax = INFINITY;
    o->src = i;
}

/* The hits of the closest-hit batches as the host reads them: Hit's four
 * fields. With instances the kernels' Hit also names the instance; the
 * batches keep the four fields (t, b1, b2, tri) in hits and each hit's
 * instance in a buffer of its own (insts, CLP_BATCH_INSTS), which the
 * secondary rays read. */
#ifdef CLP_HAS_INSTANCES
#define CLP_BATCH_HITS global float4*
#define CLP_BATCH_INSTS , global const AccelNode *nodes, global int *insts
#define CLP_BATCH_INSTS_OUT , global int *insts
#else
#define CLP_BATCH_HITS global Hit*
#define CLP_BATCH_INSTS
#define CLP_BATCH_INSTS_OUT
#endif

/* The surface point primary hit k found, with its rounding-error bound and
 * its geometric normal turned towards the ray's side (in world space: an
 * instance's triangle moved as the shading moves it, scene_data.cl). */
static inline float3 batch_hit_point(global const TriVerts* tris, const BatchRay* r, CLP_BATCH_HITS hits, uint k,
                                     float3* err, float3* n CLP_BATCH_INSTS) {
#ifdef CLP_HAS_INSTANCES
    const float4 hv = hits[k];
    const float b1 = hv.y, b2 = hv.z;
    global const TriVerts* tv = &tris[as_int(hv.w)];
#else
    const float b1 = hits[k].b1, b2 = hits[k].b2;
    global const TriVerts* tv = &tris[hits[k].tri];
#endif
    float3 v0 = load3g(tv->v0), v1 = load3g(tv->v1), v2 = load3g(tv->v2);
#ifdef CLP_HAS_INSTANCES
    global const float4* im = (global const float4*)&nodes[insts[k]];
    float3 ng = instance_normal(im, cross(v1 - v0, v2 - v0));
    float3 p = instance_hit_point(im, v0, v1, v2, b1, b2, err);
#else
    float3 ng = normalize3(cross(v1 - v0, v2 - v0));
    float3 p = hit_point(v0, v1, v2, b1, b2, err);
#endif
    *n = dot(ng, load3(r->d)) < 0.0f ? ng : -ng;
    return p;
}

/* Secondary ray i starts at the hit of primary ray src[i] (the host lists the
 * primaries that hit). Shadow: towards the point light, tmax 1 = the light.
 * Diffuse: cosine-distributed about the normal on the ray's side, unbounded.
 * Origins are offset as the integrator's (offset_ray_origin). */
kernel void batch_secondary_rays(global const TriVerts* tris, global const BatchRay* primary, CLP_BATCH_HITS hits,
                                 global const uint* src, uint count, float lx, float ly, float lz, uint diffuse,
                                 uint seed, global BatchRay* out CLP_BATCH_INSTS) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint k = src[i];
    BatchRay pr = primary[k];
    float3 err, n;
#ifdef CLP_HAS_INSTANCES
    float3 p = batch_hit_point(tris, &pr, hits, k, &err, &n, nodes, insts);
#else
    float3 p = batch_hit_point(tris, &pr, hits, k, &err, &n);
#endif
    float3 w, o;
    float tmax;
    if (diffuse) {
        Rng rng = rng_seed(k, 1u, seed);
        float u1 = rng_next(&rng), u2 = rng_next(&rng);
        w = to_world(sample_cosine_hemisphere(u1, u2), n);
        o = offset_ray_origin(p, err, n, w);
        tmax = INFINITY;
    } else {
        float3 light = (float3)(lx, ly, lz);
        o = offset_ray_origin(p, err, n, light - p);
        w = light - o;
        tmax = 1.0f;
    }
    global BatchRay* r = &out[i];
    r->o[0] = o.x, r->o[1] = o.y, r->o[2] = o.z;
    r->d[0] = w.x, r->d[1] = w.y, r->d[2] = w.z;
    r->tmax = tmax;
    r->src = k;
}

/* The timed kernels: closest hit, and any hit (shadow rays). */
kernel void batch_trace_closest(global const AccelNode* nodes, global const TriVerts* tris,
                                global const BatchRay* rays, CLP_BATCH_HITS hits, uint count CLP_BATCH_INSTS_OUT) {
    uint i = get_global_id(0);
    if (i >= count) return;
    global const BatchRay* r = &rays[i];
    RayPre rp = ray_prepare(load3g(r->o), load3g(r->d));
    Hit h;
    traverse_bvh(&h, nodes, tris, &rp, r->tmax, 0, 0);
#ifdef CLP_HAS_INSTANCES
    hits[i] = (float4)(h.t, h.b1, h.b2, as_float(h.tri));
    insts[i] = h.inst;
#else
    hits[i] = h;
#endif
}

kernel void batch_trace_any(global const AccelNode* nodes, global const TriVerts* tris, global const BatchRay* rays,
                            global int* occluder, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    global const BatchRay* r = &rays[i];
    RayPre rp = ray_prepare(load3g(r->o), load3g(r->d));
    Hit h;
    traverse_bvh(&h, nodes, tris, &rp, r->tmax, 1, 0);
    occluder[i] = h.tri;
}

#endif
