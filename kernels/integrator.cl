/* The integrators: one work-item per pixel, `samples` samples each, each
 * sample added to the pixel's running sum in sample order (so the image does
 * not depend on how the host splits the work into launches). The program is
 * compiled for one integrator (CLP_INTEGRATOR) and one maximum depth
 * (CLP_MAX_DEPTH); see host/render/kernel_features.cpp. */
#ifndef CLP_INTEGRATOR_CL
#define CLP_INTEGRATOR_CL

#include "scene_data.cl"
#include "path.cl"
#include "film.cl"
#define CLP_HEATMAP_MAX 128.0f /* nodes visited that map to the top of the heat map's colour ramp */

/* ---- path tracing ------------------------------------------------------- */

/* Each integrator's integrate() is forced inline into the kernel on a GPU:
 * out of line (LLVM's choice for the larger ones) the scene, ray and random
 * state it is handed by pointer live in the GPU's off-chip stack (176 bytes
 * more at sm_90 with every feature). */

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH || CLP_INTEGRATOR == CLP_INTEGRATOR_PATH_BSDF

/* The path's bounces, one after another (path.cl); the shadow ray of each is
 * traced before the next bounce, so contributions add in the path's order. */
CLP_GPU_INLINE float3 integrate(const SceneData* sc, Ray ray, Rng* rng, uint* rays) {
    PathState ps;
    path_start(&ps, ray, *rng);
    for (;;) {
        Hit h;
        trace_closest(&h, sc, ps.ray, rays, 0);
        ShadowRay sh;
        const int more = path_step(sc, &ps, &h, &sh);
        if (sh.active) path_shadow_done(&ps.L, &sh, occluded(sc, sh.o, sh.d, sh.tmax, rays));
        if (!more) break;
    }
    *rng = ps.rng;
    return ps.L;
}

/* ---- ambient occlusion -------------------------------------------------- */

#elif CLP_INTEGRATOR == CLP_INTEGRATOR_AO
/* The fraction of the cosine-weighted hemisphere above the first hit that is
 * open within ao_distance: 1 for an open plane, 0 where nothing is hit. */
CLP_GPU_INLINE float3 integrate(const SceneData* sc, Ray ray, Rng* rng, uint* rays) {
    Hit h;
    trace_closest(&h, sc, ray, rays, 0);
    if (h.tri < 0) return (float3)(0.0f);
    Surface s;
    surface_at(&s, sc, &h, ray.d);
    float3 n = s.front ? s.ng : -s.ng;
    float u1 = rng_next(rng), u2 = rng_next(rng);
    float3 wi = to_world(sample_cosine_hemisphere(u1, u2), n);
    float3 o = offset_ray_origin(s.p, s.err, s.ng, wi);
    return (float3)(occluded(sc, o, wi, sc->fp->ao_distance, rays) ? 0.0f : 1.0f);
}

/* ---- debug views -------------------------------------------------------- */

#else
/* A blue-green-yellow-red ramp for t in [0, 1]. */
static inline float3 heat_colour(float t) {
    t = clamp(t, 0.0f, 1.0f);
    float3 c0 = (float3)(0.05f, 0.05f, 0.5f), c1 = (float3)(0.0f, 0.7f, 0.9f), c2 = (float3)(0.2f, 0.85f, 0.2f),
           c3 = (float3)(1.0f, 0.9f, 0.0f), c4 = (float3)(0.9f, 0.1f, 0.05f);
    float x = t * 4.0f;
    if (x < 1.0f) return mix(c0, c1, x);
    if (x < 2.0f) return mix(c1, c2, x - 1.0f);
    if (x < 3.0f) return mix(c2, c3, x - 2.0f);
    return mix(c3, c4, x - 3.0f);
}

CLP_GPU_INLINE float3 integrate(const SceneData* sc, Ray ray, Rng* rng, uint* rays) {
    uint visits = 0;
    Hit h;
    trace_closest(&h, sc, ray, rays, &visits);
#if CLP_INTEGRATOR == CLP_INTEGRATOR_HEATMAP
    return heat_colour((float)visits / CLP_HEATMAP_MAX);
#else
    if (h.tri < 0) return (float3)(0.0f);
    Surface s;
    surface_at(&s, sc, &h, ray.d);
#if CLP_INTEGRATOR == CLP_INTEGRATOR_NORMALS
    return s.ns * 0.5f + 0.5f;
#elif CLP_INTEGRATOR == CLP_INTEGRATOR_DEPTH
    return (float3)(h.t / sc->fp->depth_scale);
#else
    return material_albedo(surface_material(&s));
#endif
#endif
}
#endif

/* ---- the kernel --------------------------------------------------------- */

kernel void render_paths(CLP_SCENE_PARAMS constant const FrameParams* fp, global AccumPixel* accum,
                         global Counters* counters, global const uchar* active) {
    local uint group_rays, group_nonfinite;
    if (get_local_id(0) == 0) group_rays = group_nonfinite = 0;
    barrier(CLK_LOCAL_MEM_FENCE);

    SceneData sc;
    scene_data(&sc, CLP_SCENE_ARGS fp);

    uint rays = 0, nonfinite = 0, px, py;
    uint gid = get_global_id(0);
    if (gid < fp->pixel_count &&
        tile_to_pixel(fp->pixel_offset + gid, fp->camera.width, fp->camera.height, &px, &py)) {
        uint pixel = py * fp->camera.width + px;
        /* Under adaptive sampling a converged pixel takes no sample. */
        if (!fp->adaptive || active[pixel]) {
            float3 sum = load3g(accum[pixel].sum), comp = load3g(accum[pixel].comp);
            float half_sum = accum[pixel].sum[3], half_comp = accum[pixel].comp[3];
            for (uint s = 0; s < fp->samples; ++s) {
                Rng rng = rng_seed(pixel, fp->first_sample + s, fp->seed);
                float jx = rng_next(&rng), jy = rng_next(&rng);
                Ray ray = camera_ray(&fp->camera, px, py, jx, jy);
                camera_lens(&fp->camera, &rng, &ray);
                float3 L = integrate(&sc, ray, &rng, &rays);
                /* A non-finite sample would poison the pixel forever: count it, drop it. */
                if (!all(isfinite(L))) {
                    ++nonfinite;
                    L = (float3)(0.0f);
                }
                kahan_add(&sum, &comp, L);
                if (fp->adaptive && ((fp->first_sample + s) & 1u)) kahan_add1(&half_sum, &half_comp, L.x + L.y + L.z);
            }
            for (int c = 0; c < 3; ++c) {
                accum[pixel].sum[c] = c == 0 ? sum.x : (c == 1 ? sum.y : sum.z);
                accum[pixel].comp[c] = c == 0 ? comp.x : (c == 1 ? comp.y : comp.z);
            }
            if (fp->adaptive) {
                accum[pixel].sum[3] = half_sum;
                accum[pixel].comp[3] = half_comp;
            }
        }
    }
    /* One global atomic per work-group rather than per work-item. */
    atomic_add(&group_rays, rays);
    if (nonfinite) atomic_add(&group_nonfinite, nonfinite);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0) {
        atomic_add(&counters->rays, group_rays);
        if (group_nonfinite) atomic_add(&counters->nonfinite, group_nonfinite);
    }
}

#endif
