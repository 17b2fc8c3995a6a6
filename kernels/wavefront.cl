/* The wavefront integrator (Laine, Karras and Aila 2013, "Megakernels
 * considered harmful"): the path tracer of integrator.cl cut into small
 * kernels that each do one thing to every live path, so that each needs few
 * registers and the paths doing the same thing run together.
 *
 *   wf_camera      a path per pixel of the band and sample of the wave
 *   wf_trace       closest hit of each queued path's ray
 *   wf_shade       one bounce (path_step, path.cl): queues the paths that go
 *                  on and the shadow rays of next-event estimation
 *   wf_shadow      any hit of each shadow ray; unoccluded light joins its path
 *   wf_next_bounce the queue just filled becomes the one to trace
 *   wf_accumulate  each path's radiance joins its pixel's sum
 *
 * A wave is one or more consecutive samples of every pixel of a band (as many
 * as the path state holds: fewer, longer launches); waves run in sample
 * order and wf_accumulate adds a wave's radiance after all its bounces, each
 * pixel's samples in order, so every pixel's sum takes the same values in the
 * same order as in render_paths: the same bits wherever the compiled
 * arithmetic is the same.
 *
 * Path state lives in structure-of-arrays float4 rows: paths[row * capacity +
 * slot] (rows below), so each kernel reads the 16-byte rows it needs,
 * coalesced. A path's slot is j * pixel_count + its pixel's tiled index in
 * the band (gid of render_paths), for the wave's j-th sample.
 * Queues hold slots; their lengths are counts[CLP_WF_*]. */
#ifndef CLP_WAVEFRONT_CL
#define CLP_WAVEFRONT_CL

#include "scene_data.cl"
#include "path.cl"
#include "film.cl"

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH || CLP_INTEGRATOR == CLP_INTEGRATOR_PATH_BSDF

/* Rows of a path's state. */
#define CLP_WF_ROW_O 0u    /* ray origin, prev_pdf */
#define CLP_WF_ROW_D 1u    /* ray direction, random state (as bits) */
#define CLP_WF_ROW_L 2u    /* radiance, depth | prev_delta << 31 (as bits) */
#define CLP_WF_ROW_BETA 3u /* throughput */
#define CLP_WF_ROW_PREV 4u /* the vertex the ray left */
/* Rows of a shadow ray. */
#define CLP_WF_SROW_O 0u    /* origin, tmax */
#define CLP_WF_SROW_D 1u    /* direction, its path's slot (as bits) */
#define CLP_WF_SROW_BETA 2u /* the path's throughput */
#define CLP_WF_SROW_V 3u    /* the unoccluded light times BSDF and MIS weight */

static inline void wf_store(global float4* paths, uint capacity, uint slot, const PathState* ps) {
    paths[CLP_WF_ROW_O * capacity + slot] = (float4)(ps->ray.o, ps->prev_pdf);
    paths[CLP_WF_ROW_D * capacity + slot] = (float4)(ps->ray.d, as_float(ps->rng.state));
    paths[CLP_WF_ROW_L * capacity + slot] =
        (float4)(ps->L, as_float(ps->depth | (ps->prev_delta ? 0x80000000u : 0u)));
    paths[CLP_WF_ROW_BETA * capacity + slot] = (float4)(ps->beta, 0.0f);
    paths[CLP_WF_ROW_PREV * capacity + slot] = (float4)(ps->prev_p, 0.0f);
}

static inline void wf_load(PathState* out, global const float4* paths, uint capacity, uint slot) {
    PathState ps;
    float4 o = paths[CLP_WF_ROW_O * capacity + slot], d = paths[CLP_WF_ROW_D * capacity + slot];
    float4 l = paths[CLP_WF_ROW_L * capacity + slot];
    ps.ray.o = o.xyz;
    ps.prev_pdf = o.w;
    ps.ray.d = d.xyz;
    ps.rng.state = as_uint(d.w);
    ps.L = l.xyz;
    ps.depth = as_uint(l.w) & 0x7fffffffu;
    ps.prev_delta = (as_uint(l.w) >> 31) != 0u;
    ps.beta = paths[CLP_WF_ROW_BETA * capacity + slot].xyz;
    ps.prev_p = paths[CLP_WF_ROW_PREV * capacity + slot].xyz;
    *out = ps;
}

/* Adds a work-item's count to *total with one atomic per work-group. */
static inline void wf_count(local uint* group, uint n, global uint* total) {
    if (get_local_id(0) == 0) *group = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (n) atomic_add(group, n);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && *group) atomic_add(total, *group);
}

kernel void wf_camera(constant const FrameParams* fp, uint first, uint samples, global float4* paths,
                      uint capacity, global uint* queue, global uint* counts, global const uchar* active) {
    /* Path slot = j * pixel_count + the pixel's slot in the band: sample
     * first + j of that pixel. */
    uint slot = get_global_id(0), px, py;
    if (slot >= fp->pixel_count * samples) return;
    uint j = slot / fp->pixel_count;
    if (!tile_to_pixel(fp->pixel_offset + slot - j * fp->pixel_count, fp->camera.width, fp->camera.height, &px, &py))
        return;
    /* Under adaptive sampling a converged pixel starts no path (wf_accumulate skips it too). */
    if (fp->adaptive && !active[py * fp->camera.width + px]) return;
    Rng rng = rng_seed(py * fp->camera.width + px, fp->first_sample + first + j, fp->seed);
    float jx = rng_next(&rng), jy = rng_next(&rng);
    Ray ray = camera_ray(&fp->camera, px, py, jx, jy);
    camera_lens(&fp->camera, &rng, &ray);
    PathState ps;
    path_start(&ps, ray, rng);
    wf_store(paths, capacity, slot, &ps);
    queue[atomic_inc(&counts[CLP_WF_QUEUED])] = slot;
}

kernel void wf_trace(CLP_SCENE_PARAMS constant const FrameParams* fp, global const float4* paths, uint capacity,
                     global const uint* queue, global const uint* counts, global float4* hits,
                     global Counters* counters) {
    local uint group_rays;
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0), rays = 0;
    if (i < counts[CLP_WF_QUEUED]) {
        uint slot = queue[i];
        Ray ray;
        ray.o = paths[CLP_WF_ROW_O * capacity + slot].xyz;
        ray.d = paths[CLP_WF_ROW_D * capacity + slot].xyz;
        Hit h;
        trace_closest(&h, &sc, ray, &rays, 0);
        hits[slot] = (float4)(h.t, h.b1, h.b2, as_float(h.tri));
    }
    wf_count(&group_rays, rays, &counters->rays);
}

kernel void wf_shade(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                     global const uint* queue, global uint* next_queue, global uint* counts,
                     global const float4* hits, global float4* shadows) {
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0);
    if (i >= counts[CLP_WF_QUEUED]) return;
    uint slot = queue[i];
    PathState ps;
    wf_load(&ps, paths, capacity, slot);
    float4 hv = hits[slot];
    Hit h;
    h.t = hv.x;
    h.b1 = hv.y;
    h.b2 = hv.z;
    h.tri = as_int(hv.w);
    ShadowRay sh;
    int more = path_step(&sc, &ps, &h, &sh);
    wf_store(paths, capacity, slot, &ps);
    if (more) next_queue[atomic_inc(&counts[CLP_WF_NEXT])] = slot;
    if (sh.active) {
        uint k = atomic_inc(&counts[CLP_WF_SHADOWS]);
        shadows[CLP_WF_SROW_O * capacity + k] = (float4)(sh.o, sh.tmax);
        shadows[CLP_WF_SROW_D * capacity + k] = (float4)(sh.d, as_float(slot));
        shadows[CLP_WF_SROW_BETA * capacity + k] = (float4)(sh.beta, 0.0f);
        shadows[CLP_WF_SROW_V * capacity + k] = (float4)(sh.v, 0.0f);
    }
}

kernel void wf_shadow(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                      global const uint* counts, global const float4* shadows, global Counters* counters) {
    local uint group_rays;
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint k = get_global_id(0), rays = 0;
    if (k < counts[CLP_WF_SHADOWS]) {
        float4 o = shadows[CLP_WF_SROW_O * capacity + k], d = shadows[CLP_WF_SROW_D * capacity + k];
        ShadowRay sh;
        sh.o = o.xyz;
        sh.tmax = o.w;
        sh.d = d.xyz;
        sh.active = 1;
        /* The contribution and the path's radiance are read only once the
         * light is found unoccluded, so that the walk keeps nothing else
         * live (read before it, they took 70 registers at sm_90). */
        if (!occluded(&sc, sh.o, sh.d, sh.tmax, &rays)) {
            sh.beta = shadows[CLP_WF_SROW_BETA * capacity + k].xyz;
            sh.v = shadows[CLP_WF_SROW_V * capacity + k].xyz;
            uint slot = as_uint(d.w);
            float4 l = paths[CLP_WF_ROW_L * capacity + slot];
            float3 L = l.xyz;
            path_shadow_done(&L, &sh, 0);
            paths[CLP_WF_ROW_L * capacity + slot] = (float4)(L, l.w);
        }
    }
    wf_count(&group_rays, rays, &counters->rays);
}

/* The queue wf_shade filled is the next one to trace; the shadow list is emptied. */
kernel void wf_next_bounce(global uint* counts) {
    counts[CLP_WF_QUEUED] = counts[CLP_WF_NEXT];
    counts[CLP_WF_NEXT] = 0;
    counts[CLP_WF_SHADOWS] = 0;
}

/* The wave's radiance joins each pixel's compensated sum, its samples in
 * order, as render_paths adds them (first: the wave's first sample in the
 * launch, for the adaptive half film's odd samples). */
kernel void wf_accumulate(constant const FrameParams* fp, uint samples, global const float4* paths, uint capacity,
                          global AccumPixel* accum, global Counters* counters, global const uchar* active,
                          uint first) {
    local uint group_nonfinite;
    uint slot = get_global_id(0), px, py, nonfinite = 0;
    if (slot < fp->pixel_count &&
        tile_to_pixel(fp->pixel_offset + slot, fp->camera.width, fp->camera.height, &px, &py)) {
        uint pixel = py * fp->camera.width + px;
        if (!fp->adaptive || active[pixel]) {
            float3 sum = load3g(accum[pixel].sum), comp = load3g(accum[pixel].comp);
            float half_sum = accum[pixel].sum[3], half_comp = accum[pixel].comp[3];
            for (uint j = 0; j < samples; ++j) {
                float3 L = paths[CLP_WF_ROW_L * capacity + j * fp->pixel_count + slot].xyz;
                if (!all(isfinite(L))) {
                    ++nonfinite;
                    L = (float3)(0.0f);
                }
                kahan_add(&sum, &comp, L);
                if (fp->adaptive && ((fp->first_sample + first + j) & 1u))
                    kahan_add1(&half_sum, &half_comp, L.x + L.y + L.z);
            }
            accum[pixel].sum[0] = sum.x;
            accum[pixel].sum[1] = sum.y;
            accum[pixel].sum[2] = sum.z;
            accum[pixel].comp[0] = comp.x;
            accum[pixel].comp[1] = comp.y;
            accum[pixel].comp[2] = comp.z;
            if (fp->adaptive) {
                accum[pixel].sum[3] = half_sum;
                accum[pixel].comp[3] = half_comp;
            }
        }
    }
    wf_count(&group_nonfinite, nonfinite, &counters->nonfinite);
}

#endif
#endif
