/* The wavefront integrator (Laine, Karras and Aila 2013, "Megakernels
 * considered harmful"): the path tracer of integrator.cl cut into small
 * kernels that each do one thing to every live path, so that each needs few
 * registers and the paths doing the same thing run together.
 *
 *   wf_camera      a path per pixel of the band and sample of the wave
 *   wf_trace       closest hit of each queued path's ray
 *   wf_shade       what each path's ray sees, Russian roulette (path_miss,
 *                  path_roulette; path.cl): queues the paths that scatter
 *   wf_light       next-event estimation's light sample (path_light_sample)
 *   wf_connect     its shadow ray (path_light_eval, path_light_join)
 *   wf_scatter     the BSDF sample (path_scatter, path_follow): queues the
 *                  paths that go on
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
 * Queues hold slots; their lengths are counts[CLP_WF_*].
 *
 * A bounce is cut where a kernel holding all of it would need the most
 * registers: shading every material, sampling a light (Arvo's spherical
 * triangles) and the BSDF in one kernel took 71-110 registers at sm_90, the
 * lights' and the BSDF's state live at once. Each phase runs the functions
 * path_step runs, on the values it would have (the surface is recomputed from
 * the hit, the light sample kept in the path state), drawing from the path's
 * random stream in path_step's order. */
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
#define CLP_WF_ROW_BETA 3u /* throughput, the light BVH's normal at the vertex the ray left (PathState.prev_n, as bits) */
#define CLP_WF_ROW_PREV 4u /* the vertex the ray left (stored by wf_shade when the ray
                              reaches it), whether wf_light samples a light there */
#define CLP_WF_ROW_LS_WI 5u /* the light sample's direction, pdf */
#define CLP_WF_ROW_LS_L 6u  /* its radiance, lit | infinite << 1 | delta << 2 (as bits) */
#define CLP_WF_ROW_LS_TO 7u /* the point sampled on the light */
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
    const float4 beta = paths[CLP_WF_ROW_BETA * capacity + slot];
    ps.beta = beta.xyz;
#ifdef CLP_LIGHT_BVH
    ps.prev_n = as_uint(beta.w);
#endif
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
#ifdef CLP_HAS_INSTANCES
        ((global int*)(hits + capacity))[slot] = h.inst; /* after the hits' rows (integrator_program.cpp) */
#endif
    }
    wf_count(&group_rays, rays, &counters->rays);
}

static inline void wf_load_hit(Hit* h, global const float4* hits, uint slot) {
    float4 hv = hits[slot];
    h->t = hv.x;
    h->b1 = hv.y;
    h->b2 = hv.z;
    h->tri = as_int(hv.w);
}
#ifdef CLP_HAS_INSTANCES
/* The instance of a stored hit: an int per path after the hits' rows (wf_trace). */
static inline int wf_hit_instance(global const float4* hits, uint capacity, uint slot) {
    return ((global const int*)(hits + capacity))[slot];
}
#endif

/* A path's random state alone (the last field of its direction's row). */
static inline global uint* wf_rng_state(global float4* paths, uint capacity, uint slot) {
    return (global uint*)&paths[CLP_WF_ROW_D * capacity + slot] + 3;
}

/* The radiance row alone: all that is read of a path that has ended. */
static inline void wf_store_L(global float4* paths, uint capacity, uint slot, const PathState* ps) {
    paths[CLP_WF_ROW_L * capacity + slot] =
        (float4)(ps->L, as_float(ps->depth | (ps->prev_delta ? 0x80000000u : 0u)));
}

kernel void wf_shade(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                     global const uint* queue, global uint* scatter_queue, global uint* counts,
                     global const float4* hits) {
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0);
    if (i >= counts[CLP_WF_QUEUED]) return;
    uint slot = queue[i];
    PathState ps;
    wf_load(&ps, paths, capacity, slot);
    Hit h;
    wf_load_hit(&h, hits, slot);
#ifdef CLP_HAS_INSTANCES
    h.inst = wf_hit_instance(hits, capacity, slot);
#endif
    if (h.tri < 0) {
        path_miss(&sc, &ps);
        wf_store_L(paths, capacity, slot, &ps);
        return;
    }
    Surface s;
    surface_at(&s, &sc, &h, ps.ray.d);
    /* The vertex reached, for wf_light, stored at once: not kept through the
     * emission's MIS weight (the vertex left is read before). */
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    const uint light = path_wants_light(&sc, &s);
#else
    const uint light = 0;
#endif
    paths[CLP_WF_ROW_PREV * capacity + slot] = (float4)(s.p, as_float(light));
#ifdef CLP_LIGHT_BVH
    ((global uint*)&paths[CLP_WF_ROW_BETA * capacity + slot])[3] = lbvh_encode_normal(s.ng);
#endif
    const float w = surface_emits(&s) ? path_emission_weight(&sc, &ps, &h, &s) : 1.0f;
    /* The radiance and throughput, read again only now: not kept through the
     * emission's weight (the light BVH's walk, CLP_LIGHT_BVH). */
    ps.L = paths[CLP_WF_ROW_L * capacity + slot].xyz;
    ps.beta = paths[CLP_WF_ROW_BETA * capacity + slot].xyz;
    path_add_emission(&ps, &s, w);
    const int scatters = path_survives(&sc, &ps, &s);
    wf_store_L(paths, capacity, slot, &ps);
    if (!scatters) return;
    wf_rng_state(paths, capacity, slot)[0] = ps.rng.state;
#ifdef CLP_LIGHT_BVH
    /* The normal wf_light weighs lights with, and the next vertex's MIS weight. */
    vstore3(ps.beta, 0, (global float*)&paths[CLP_WF_ROW_BETA * capacity + slot]);
#else
    paths[CLP_WF_ROW_BETA * capacity + slot] = (float4)(ps.beta, 0.0f);
#endif
    scatter_queue[atomic_inc(&counts[CLP_WF_SCATTER])] = slot;
}

/* Every path queued to scatter: a light sample where wf_shade asked for one. */
kernel void wf_light(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                     global const uint* queue, global const uint* counts) {
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0);
    if (i >= counts[CLP_WF_SCATTER]) return;
    uint slot = queue[i];
    float4 p = paths[CLP_WF_ROW_PREV * capacity + slot];
    if (!as_uint(p.w)) return;
    /* The numbers drawn and the random state stored at once, so that it is
     * not kept through the sampling. */
    Rng rng;
    rng.state = wf_rng_state(paths, capacity, slot)[0];
    float u0 = rng_next(&rng), u1 = rng_next(&rng), u2 = rng_next(&rng);
    wf_rng_state(paths, capacity, slot)[0] = rng.state;
    LightSample ls;
#ifdef CLP_LIGHT_BVH
    const float3 n = lbvh_octahedral(as_uint(paths[CLP_WF_ROW_BETA * capacity + slot].w));
#else
    const float3 n = (float3)(0.0f);
#endif
    const int lit = path_light_sample(&sc, p.xyz, n, u0, u1, u2, &ls);
    paths[CLP_WF_ROW_LS_WI * capacity + slot] = (float4)(ls.wi, ls.pdf);
    paths[CLP_WF_ROW_LS_L * capacity + slot] =
        (float4)(ls.L, as_float((uint)lit | (uint)ls.infinite << 1 | (uint)ls.delta << 2));
    paths[CLP_WF_ROW_LS_TO * capacity + slot] = (float4)(ls.to, 0.0f);
#endif
}

/* Every path queued to scatter that sampled a light: its shadow ray (or the
 * zero contribution added at once). */
kernel void wf_connect(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                       global const uint* queue, global uint* counts, global const float4* hits,
                       global float4* shadows) {
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0);
    if (i >= counts[CLP_WF_SCATTER]) return;
    uint slot = queue[i];
    if (!as_uint(paths[CLP_WF_ROW_PREV * capacity + slot].w)) return;
    const float3 d = paths[CLP_WF_ROW_D * capacity + slot].xyz;
    Hit h;
    wf_load_hit(&h, hits, slot);
#ifdef CLP_HAS_INSTANCES
    h.inst = wf_hit_instance(hits, capacity, slot);
#endif
    Surface s;
    surface_at(&s, &sc, &h, d);
    LightSample ls;
    float4 wi = paths[CLP_WF_ROW_LS_WI * capacity + slot], ll = paths[CLP_WF_ROW_LS_L * capacity + slot];
    ls.wi = wi.xyz;
    ls.pdf = wi.w;
    ls.L = ll.xyz;
    ls.infinite = (as_uint(ll.w) >> 1) & 1u;
    ls.delta = (as_uint(ll.w) >> 2) & 1u;
    ls.to = paths[CLP_WF_ROW_LS_TO * capacity + slot].xyz;
    ShadowRay sh;
    const float3 v = path_light_eval(&s, -d, &ls, as_uint(ll.w) & 1u, &sh);
    /* The path's radiance and throughput, read only now (not kept through
     * the BSDF's evaluation). */
    PathState ps;
    float4 l = paths[CLP_WF_ROW_L * capacity + slot];
    ps.L = l.xyz;
    ps.beta = paths[CLP_WF_ROW_BETA * capacity + slot].xyz;
    path_light_join(&ps, v, &sh);
    paths[CLP_WF_ROW_L * capacity + slot] = (float4)(ps.L, l.w);
    if (sh.active) {
        uint k = atomic_inc(&counts[CLP_WF_SHADOWS]);
        shadows[CLP_WF_SROW_O * capacity + k] = (float4)(sh.o, sh.tmax);
        shadows[CLP_WF_SROW_D * capacity + k] = (float4)(sh.d, as_float(slot));
        shadows[CLP_WF_SROW_BETA * capacity + k] = (float4)(sh.beta, 0.0f);
        shadows[CLP_WF_SROW_V * capacity + k] = (float4)(sh.v, 0.0f);
    }
#endif
}

/* Every path queued to scatter: the BSDF sample for its next ray. */
kernel void wf_scatter(CLP_SCENE_PARAMS constant const FrameParams* fp, global float4* paths, uint capacity,
                       global const uint* queue, global uint* next_queue, global uint* counts,
                       global const float4* hits) {
    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);
    uint i = get_global_id(0);
    if (i >= counts[CLP_WF_SCATTER]) return;
    uint slot = queue[i];
    /* A path whose next ray could add no light ends after its light sample,
     * as in path_step; where path_next_ray_gathers is always 1 the read is
     * dead and the compiler drops it. */
    if (!path_next_ray_gathers(as_uint(paths[CLP_WF_ROW_L * capacity + slot].w) & 0x7fffffffu)) return;
    float4 d = paths[CLP_WF_ROW_D * capacity + slot];
    Rng rng;
    rng.state = as_uint(d.w);
    Hit h;
    wf_load_hit(&h, hits, slot);
#ifdef CLP_HAS_INSTANCES
    h.inst = wf_hit_instance(hits, capacity, slot);
#endif
    Surface s;
    surface_at(&s, &sc, &h, d.xyz);
    BsdfSample bs;
    if (!path_scatter(&rng, &s, -d.xyz, &bs)) return;
    /* What path_turn changes, read only now (not kept through the
     * sampling); what it replaces is not read. The radiance is not changed. */
    PathState ps;
    ps.rng = rng;
    const float4 beta = paths[CLP_WF_ROW_BETA * capacity + slot];
    ps.beta = beta.xyz;
    ps.depth = as_uint(paths[CLP_WF_ROW_L * capacity + slot].w) & 0x7fffffffu;
    path_turn(&ps, &bs);
    paths[CLP_WF_ROW_D * capacity + slot] = (float4)(ps.ray.d, as_float(ps.rng.state));
    ((global uint*)&paths[CLP_WF_ROW_L * capacity + slot])[3] = ps.depth | (ps.prev_delta ? 0x80000000u : 0u);
    paths[CLP_WF_ROW_BETA * capacity + slot] = (float4)(ps.beta, beta.w); /* the normal stays (wf_shade's) */
    /* The new ray's origin (path_follow's), from the hit point and its error
     * bound recomputed after the stores above rather than kept through the
     * BSDF sampling: kept, they took 65-67 registers at sm_90 in programs with
     * GGX conductors or glass, recomputed 58-60. The stores may alias the
     * triangles as far as the compiler knows, so it cannot merge the two
     * reads back into one and keep the values after all. The same
     * arithmetic on the same values: the same bits. ps.prev_p is the vertex
     * wf_shade stored already. */
    wf_load_hit(&h, hits, slot);
    float3 err, ng;
    const float3 p = surface_point(&sc, &h, &ng, &err);
    paths[CLP_WF_ROW_O * capacity + slot] = (float4)(offset_ray_origin(p, err, ng, bs.wi), ps.prev_pdf);
    next_queue[atomic_inc(&counts[CLP_WF_NEXT])] = slot;
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

/* The queue wf_scatter filled is the next one to trace; the scatter queue and
 * the shadow list are emptied. */
kernel void wf_next_bounce(global uint* counts) {
    counts[CLP_WF_QUEUED] = counts[CLP_WF_NEXT];
    counts[CLP_WF_NEXT] = 0;
    counts[CLP_WF_SCATTER] = 0;
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
