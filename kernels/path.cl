/* One path's state between bounces, and the step from one bounce to the
 * next: what the megakernel's loop (integrator.cl) and the wavefront's
 * shading kernel (wavefront.cl) both run, so the two integrator shapes share
 * one estimator and, where the arithmetic is the same, give the same bits.
 *
 * A step, given the closest hit of the path's ray (or a miss), adds what the
 * ray sees (emission or the environment, MIS-weighted against light sampling
 * at the vertex the ray left), plays Russian roulette, prepares next-event
 * estimation's shadow ray (its contribution is added once the ray is found
 * unoccluded: path_shadow_done) and samples the BSDF for the next ray. The
 * random numbers are drawn in the order the path has always drawn them. */
#ifndef CLP_PATH_CL
#define CLP_PATH_CL

#include "scene_data.cl"

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH || CLP_INTEGRATOR == CLP_INTEGRATOR_PATH_BSDF

typedef struct {
    Ray ray;         /* the ray to trace next */
    float3 L, beta;  /* radiance so far, throughput */
    float3 prev_p;   /* the vertex the ray left: light pdfs for MIS are taken from there */
    float prev_pdf;  /* the BSDF pdf of the ray's direction */
    int prev_delta;  /* the ray left a delta lobe (or the camera): what it sees was never light-sampled */
    uint depth;      /* bounces so far */
    Rng rng;
} PathState;

/* Next-event estimation's shadow ray: the light's contribution beta v counts
 * when nothing lies on o + d t, t in (0, tmax). beta and v stay apart so the
 * radiance is updated by the one expression L += beta * v wherever the ray
 * is resolved (a compiler may fuse it into one multiply-add). */
typedef struct {
    float3 o, d, beta, v;
    float tmax;
    int active;
} ShadowRay;

/* A path leaving the camera along ray, its random stream after the jitter. */
static inline void path_start(PathState* ps, Ray ray, Rng rng) {
    ps->ray = ray;
    ps->L = (float3)(0.0f);
    ps->beta = (float3)(1.0f);
    ps->prev_p = ray.o;
    ps->prev_pdf = 0.0f;
    ps->prev_delta = 1; /* a camera ray: what it sees directly is never light-sampled */
    ps->depth = 0;
    ps->rng = rng;
}

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
/* Next-event estimation: light sampled at a surface, weighted against BSDF
 * sampling of the same path by the power heuristic (Veach 1997, ch. 9).
 * Returns the unoccluded contribution; *sh gets the shadow ray that decides
 * it (inactive where the sample gives nothing). */
static inline float3 sample_direct(const SceneData* sc, const Surface* s, float3 wo, Rng* rng, ShadowRay* sh) {
    sh->active = 0;
    LightSample ls;
    float u0 = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
    if (!sample_light(sc->lights, sc->alias, sc->fp, &sc->env, s->p, u0, u1, u2, &ls)) return (float3)(0.0f);
    float bsdf_pdf;
    float3 f = material_eval(surface_material(s), s->ng, s->ns, wo, ls.wi, &bsdf_pdf);
    if (!(max3(f) > 0.0f) || !(max3(ls.L) > 0.0f)) return (float3)(0.0f);
    float3 o = offset_ray_origin(s->p, s->err, s->ng, ls.wi);
    sh->active = 1;
    sh->o = o;
    sh->d = ls.infinite ? ls.wi : ls.to - o;
    sh->tmax = ls.infinite ? INFINITY : 1.0f;
    float w = ls.delta ? 1.0f : power_heuristic(ls.pdf, bsdf_pdf);
    return f * ls.L * (w / ls.pdf);
}
#endif

/* One bounce: h is the closest hit of ps->ray (tri < 0: a miss). Returns 1
 * when the path goes on along ps->ray, 0 when it has ended. *sh is the
 * shadow ray to resolve before the next step (path_shadow_done). */
static inline int path_step(const SceneData* sc, PathState* ps, const Hit* h, ShadowRay* sh) {
    sh->active = 0;
    if (h->tri < 0) {
#ifdef CLP_HAS_ENV
        float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
        if (!ps->prev_delta && sc->fp->env_light != CLP_NO_LIGHT)
            w = power_heuristic(ps->prev_pdf,
                                sc->alias[sc->fp->env_light].pmf * env_pdf(sc->fp, &sc->env, ps->ray.d));
#endif
        ps->L += ps->beta * w * env_radiance(sc->fp, &sc->env, ps->ray.d);
#endif
        return 0;
    }
    Surface s;
    surface_at(&s, sc, h, ps->ray.d);
#ifdef CLP_HAS_EMISSION
    float3 Le = material_emission(surface_material(&s), s.front);
    if (max3(Le) > 0.0f) {
        float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH && defined(CLP_HAS_TRIANGLE_LIGHTS)
        if (!ps->prev_delta && s.tv->light != CLP_NO_LIGHT)
            w = power_heuristic(ps->prev_pdf,
                                triangle_light_pdf(sc->lights, sc->alias, s.tv->light, ps->prev_p, ps->ray.d, h->t));
#endif
        ps->L += ps->beta * w * Le;
    }
#endif
    if (ps->depth >= CLP_MAX_DEPTH || !material_scatters(surface_material(&s))) return 0;
    if (!russian_roulette(sc->fp, ps->depth, &ps->beta, &ps->rng)) return 0;
    float3 wo = -ps->ray.d;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    if (sc->fp->light_count > 0 && !material_is_delta(surface_material(&s))) {
        float3 v = sample_direct(sc, &s, wo, &ps->rng, sh);
        if (sh->active) {
            sh->beta = ps->beta;
            sh->v = v;
            /* A throughput that is not finite poisons the radiance whether the
             * light is seen or not (the sample is then dropped as non-finite). */
            if (!all(isfinite(ps->beta))) ps->L += ps->beta * (float3)(0.0f);
        } else {
            ps->L += ps->beta * v;
        }
    }
#endif
    BsdfSample bs;
    float u1 = rng_next(&ps->rng), u2 = rng_next(&ps->rng), u3 = rng_next(&ps->rng);
    if (!material_sample(surface_material(&s), s.ng, s.ns, wo, u1, u2, u3, &bs)) return 0;
    ps->beta *= bs.weight;
    ps->prev_pdf = bs.pdf;
    ps->prev_delta = bs.delta;
    ps->prev_p = s.p;
    ps->ray.o = offset_ray_origin(s.p, s.err, s.ng, bs.wi);
    ps->ray.d = bs.wi;
    ++ps->depth;
    return 1;
}

/* The shadow ray's verdict: its contribution joins the path's radiance when
 * the light is unoccluded. */
static inline void path_shadow_done(float3* L, const ShadowRay* sh, int occluded_light) {
    if (!occluded_light) *L += sh->beta * sh->v;
}

#endif
#endif
