/* The integrators: one work-item per pixel, `samples` samples each, each
 * sample added to the pixel's running sum in sample order (so the image does
 * not depend on how the host splits the work into launches). The program is
 * compiled for one integrator (CLP_INTEGRATOR) and one maximum depth
 * (CLP_MAX_DEPTH); see host/render/kernel_features.cpp. */
#ifndef CLP_INTEGRATOR_CL
#define CLP_INTEGRATOR_CL

#include "common.h"
#include "rng.cl"
#include "sampling.cl"
#include "camera.cl"
#include "traverse.cl"
#include "materials.cl"
#include "surface_params.cl"
#include "lights.cl"
#include "film.cl"

/* Both come from the host's settings, never from a default here. */
#if !defined(CLP_INTEGRATOR) || !defined(CLP_MAX_DEPTH)
#error "build with -DCLP_INTEGRATOR and -DCLP_MAX_DEPTH (host/render/kernel_features.cpp build_options)"
#endif
#define CLP_HEATMAP_MAX 128.0f /* nodes visited that map to the top of the heat map's colour ramp */

/* Everything a path needs to know about the scene, gathered once per work-item. */
typedef struct {
    global const AccelNode* nodes;
    global const TriVerts* tris;
    global const uint* tri_material;
    global const Material* materials;
    global const float* normals; /* 9 floats per scene triangle (CLP_HAS_NORMALS) */
    global const Light* lights;
    global const AliasEntry* alias;
    EnvMap env;
    constant const FrameParams* fp;
#if defined(CLP_SURFACE_PARAMS) || defined(CLP_HAS_ALPHA)
    SurfaceData sd; /* textures, vertex attributes, material extensions (textures.cl): only where read */
#endif
#ifdef CLP_HAS_ALPHA
    AlphaScene alpha;
#endif
} SceneData;

#ifdef CLP_HAS_ALPHA
#define CLP_SCENE_ALPHA , &sc->alpha
#else
#define CLP_SCENE_ALPHA
#endif

static inline int tile_to_pixel(uint i, uint width, uint height, uint* px, uint* py) {
    uint tiles_x = (width + CLP_TILE - 1) / CLP_TILE;
    uint tile = i / (CLP_TILE * CLP_TILE), in = i % (CLP_TILE * CLP_TILE);
    *px = (tile % tiles_x) * CLP_TILE + in % CLP_TILE;
    *py = (tile / tiles_x) * CLP_TILE + in / CLP_TILE;
    return *px < width && *py < height;
}

static inline float max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

/* Russian roulette: returns 0 to end the path, else divides the throughput by
 * the survival probability, which keeps the estimate unbiased. */
static inline int russian_roulette(constant const FrameParams* fp, uint depth, float3* beta, Rng* rng) {
    float q = 1.0f;
    if (fp->rr_rule == CLP_RR_THROUGHPUT && depth >= fp->rr_min_depth)
        q = fmin(max3(*beta), 1.0f);
    else if (fp->rr_rule == CLP_RR_DEPTH)
        q = 1.0f - 1.0f / (float)(CLP_MAX_DEPTH - depth); /* the thesis renderer's rule */
    if (q >= 1.0f) return 1;
    if (q <= 0.0f || rng_next(rng) >= q) return 0;
    *beta /= q;
    return 1;
}

/* ---- surfaces ----------------------------------------------------------- */

typedef struct {
    float3 p, err; /* hit point and its rounding-error bound */
    float3 ng;     /* geometric normal of the winding (unit) */
    float3 ns;     /* shading normal (unit), interpolated when the mesh has normals */
    int front;     /* the ray arrived on the front side */
    global const TriVerts* tv;
    global const Material* m;
#ifdef CLP_SURFACE_PARAMS
    Material mat; /* m with this point's textures and vertex colour applied (surface_params.cl) */
#endif
} Surface;

#ifdef CLP_SURFACE_PARAMS
#define surface_material(s) (&(s)->mat)
#else
#define surface_material(s) ((s)->m)
#endif

/* The surface a hit found, written to *out (not returned: see no_hit in traverse_leaf.cl). */
static inline void surface_at(Surface* out, const SceneData* sc, const Hit* h, float3 d) {
    Surface s;
    s.tv = &sc->tris[h->tri];
    float3 v0 = load3g(s.tv->v0), v1 = load3g(s.tv->v1), v2 = load3g(s.tv->v2);
    s.ng = normalize3(cross(v1 - v0, v2 - v0));
    s.front = dot(s.ng, d) < 0.0f;
    s.p = hit_point(v0, v1, v2, h->b1, h->b2, &s.err);
    uint mi = sc->tri_material[s.tv->prim];
    s.m = &sc->materials[mi];
    s.ns = s.ng;
#ifdef CLP_HAS_NORMALS
    if (sc->fp->scene_flags & CLP_SCENE_NORMALS) {
    global const float* n = sc->normals + 9 * (size_t)s.tv->prim;
    float3 ns = (1.0f - h->b1 - h->b2) * vload3(0, n) + h->b1 * vload3(1, n) + h->b2 * vload3(2, n);
    float len = length3(ns);
    if (len > 0.0f && isfinite(len)) s.ns = ns / len;
    }
#endif
#ifdef CLP_SURFACE_PARAMS
    surface_params(&sc->sd, s.m, mi, s.tv, h->b1, h->b2, &s.ns, &s.mat);
#endif
    *out = s;
}

/* Any hit between o and o + d * tmax (d need not be unit). */
static inline int occluded(const SceneData* sc, float3 o, float3 d, float tmax, uint* rays) {
    RayPre rp = ray_prepare(o, d);
    ++*rays;
    Hit h;
    traverse_bvh(&h, sc->nodes, sc->tris, &rp, tmax, 1, 0 CLP_SCENE_ALPHA);
    return h.tri >= 0;
}

static inline void trace_closest(Hit* h, const SceneData* sc, Ray ray, uint* rays, uint* visits) {
    RayPre rp = ray_prepare(ray.o, ray.d);
    ++*rays;
    traverse_bvh(h, sc->nodes, sc->tris, &rp, INFINITY, 0, visits CLP_SCENE_ALPHA);
}

/* ---- path tracing ------------------------------------------------------- */

/* Each integrator's integrate() is forced inline into the kernel on a GPU:
 * out of line (LLVM's choice for the larger ones) the scene, ray and random
 * state it is handed by pointer live in the GPU's off-chip stack (176 bytes
 * more at sm_90 with every feature). */
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH || CLP_INTEGRATOR == CLP_INTEGRATOR_PATH_BSDF

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
/* Next-event estimation: light sampled at a surface, weighted against BSDF
 * sampling of the same path by the power heuristic (Veach 1997, ch. 9). */
static inline float3 sample_direct(const SceneData* sc, const Surface* s, float3 wo, Rng* rng, uint* rays) {
    LightSample ls;
    float u0 = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
    if (!sample_light(sc->lights, sc->alias, sc->fp, &sc->env, s->p, u0, u1, u2, &ls)) return (float3)(0.0f);
    float bsdf_pdf;
    float3 f = material_eval(surface_material(s), s->ng, s->ns, wo, ls.wi, &bsdf_pdf);
    if (!(max3(f) > 0.0f) || !(max3(ls.L) > 0.0f)) return (float3)(0.0f);
    float3 o = offset_ray_origin(s->p, s->err, s->ng, ls.wi);
    if (ls.infinite ? occluded(sc, o, ls.wi, INFINITY, rays) : occluded(sc, o, ls.to - o, 1.0f, rays))
        return (float3)(0.0f);
    float w = ls.delta ? 1.0f : power_heuristic(ls.pdf, bsdf_pdf);
    return f * ls.L * (w / ls.pdf);
}
#endif

CLP_GPU_INLINE float3 integrate(const SceneData* sc, Ray ray, Rng* rng, uint* rays) {
    constant const FrameParams* fp = sc->fp;
    float3 L = (float3)(0.0f), beta = (float3)(1.0f);
    float prev_pdf = 0.0f;
    float3 prev_p = ray.o; /* the vertex the ray left: light pdfs for MIS are taken from there */
    int prev_delta = 1; /* a camera ray: what it sees directly is never light-sampled */
    for (uint depth = 0;; ++depth) {
        Hit h;
        trace_closest(&h, sc, ray, rays, 0);
        if (h.tri < 0) {
#ifdef CLP_HAS_ENV
            float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
            if (!prev_delta && fp->env_light != CLP_NO_LIGHT)
                w = power_heuristic(prev_pdf, sc->alias[fp->env_light].pmf * env_pdf(fp, &sc->env, ray.d));
#endif
            L += beta * w * env_radiance(fp, &sc->env, ray.d);
#endif
            break;
        }
        Surface s;
        surface_at(&s, sc, &h, ray.d);
#ifdef CLP_HAS_EMISSION
        float3 Le = material_emission(surface_material(&s), s.front);
        if (max3(Le) > 0.0f) {
            float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH && defined(CLP_HAS_TRIANGLE_LIGHTS)
            if (!prev_delta && s.tv->light != CLP_NO_LIGHT)
                w = power_heuristic(prev_pdf, triangle_light_pdf(sc->lights, sc->alias, s.tv->light, prev_p, ray.d, h.t));
#endif
            L += beta * w * Le;
        }
#endif
        if (depth >= CLP_MAX_DEPTH || !material_scatters(surface_material(&s))) break;
        if (!russian_roulette(fp, depth, &beta, rng)) break;
        float3 wo = -ray.d;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
        if (fp->light_count > 0 && !material_is_delta(surface_material(&s))) L += beta * sample_direct(sc, &s, wo, rng, rays);
#endif
        BsdfSample bs;
        float u1 = rng_next(rng), u2 = rng_next(rng), u3 = rng_next(rng);
        if (!material_sample(surface_material(&s), s.ng, s.ns, wo, u1, u2, u3, &bs)) break;
        beta *= bs.weight;
        prev_pdf = bs.pdf;
        prev_delta = bs.delta;
        prev_p = s.p;
        ray.o = offset_ray_origin(s.p, s.err, s.ng, bs.wi);
        ray.d = bs.wi;
    }
    return L;
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
                         global Counters* counters) {
    local uint group_rays, group_nonfinite;
    if (get_local_id(0) == 0) group_rays = group_nonfinite = 0;
    barrier(CLK_LOCAL_MEM_FENCE);

    SceneData sc;
    sc.nodes = nodes;
    sc.tris = tris;
    sc.tri_material = tri_material;
    sc.materials = materials;
    sc.normals = normals;
    sc.lights = lights;
    sc.alias = alias;
    sc.env.pixels = env_pixels;
    sc.env.cdf = env_cdf;
    sc.fp = fp;
#if defined(CLP_SURFACE_PARAMS) || defined(CLP_HAS_ALPHA)
    sc.sd.desc = tex_desc;
    sc.sd.texels = texels;
    sc.sd.attrs = attrs;
    sc.sd.material_ext = material_ext;
    sc.sd.attr_stride = fp->attr_stride;
    sc.sd.flags = fp->scene_flags;
#endif
#ifdef CLP_HAS_ALPHA
    sc.alpha.sd = sc.sd;
    sc.alpha.tri_material = tri_material;
#endif

    uint rays = 0, nonfinite = 0, px, py;
    uint gid = get_global_id(0);
    if (gid < fp->pixel_count &&
        tile_to_pixel(fp->pixel_offset + gid, fp->camera.width, fp->camera.height, &px, &py)) {
        uint pixel = py * fp->camera.width + px;
        float3 sum = load3g(accum[pixel].sum), comp = load3g(accum[pixel].comp);
        for (uint s = 0; s < fp->samples; ++s) {
            Rng rng = rng_seed(pixel, fp->first_sample + s, fp->seed);
            float jx = rng_next(&rng), jy = rng_next(&rng);
            Ray ray = camera_ray(&fp->camera, px, py, jx, jy);
            float3 L = integrate(&sc, ray, &rng, &rays);
            /* A non-finite sample would poison the pixel forever: count it, drop it. */
            if (!all(isfinite(L))) {
                ++nonfinite;
                L = (float3)(0.0f);
            }
            kahan_add(&sum, &comp, L);
        }
        for (int c = 0; c < 3; ++c) {
            accum[pixel].sum[c] = c == 0 ? sum.x : (c == 1 ? sum.y : sum.z);
            accum[pixel].comp[c] = c == 0 ? comp.x : (c == 1 ? comp.y : comp.z);
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
