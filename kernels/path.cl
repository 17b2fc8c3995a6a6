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
#ifdef CLP_LIGHT_BVH
    uint prev_n;     /* the normal the light BVH picked a light with at prev_p (lbvh_encode_normal) */
#endif
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
#ifdef CLP_LIGHT_BVH
    ps->prev_n = 0u;
#endif
    ps->depth = 0;
    ps->rng = rng;
}

/* A step is cut into phases, in the order they draw random numbers, so that
 * the wavefront can run each in a kernel of its own (wavefront.cl) and the
 * megakernel runs them one after the other (path_step): the same functions
 * on the same values, so the same bits.
 *   path_miss         a ray that hit nothing: the environment it sees
 *   surface_at        (scene_data.cl) the surface a ray hit
 *   path_roulette     the surface's emission, then Russian roulette (0 or 1 draw)
 *   path_light_sample next-event estimation's light sample (3 draws, by the caller)
 *   path_light_eval   its BSDF value, MIS weight and shadow ray
 *   path_light_join   the contribution joins the path (or its shadow ray)
 *   path_scatter      the BSDF sample for the next ray (3 draws)
 *   path_follow       the path takes it (path_turn: all but the new origin) */

/* The probability that next-event estimation at the vertex the ray left
 * picked light li (is_infinite: the environment), for MIS. */
static inline float path_light_pmf(const SceneData* sc, const PathState* ps, uint li, int is_infinite) {
#ifdef CLP_LIGHT_BVH
    return light_bvh_pmf(&sc->lbvh, ps->prev_p, lbvh_octahedral(ps->prev_n), li, is_infinite);
#else
    return sc->alias[li].pmf;
#endif
}

/* A ray that left the scene: adds the environment it sees, MIS-weighted
 * against light sampling at the vertex it left. The path ends there. */
CLP_GPU_INLINE void path_miss(const SceneData* sc, PathState* ps) {
#ifdef CLP_HAS_ENV
    float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    if (!ps->prev_delta && sc->fp->env_light != CLP_NO_LIGHT)
        w = power_heuristic(ps->prev_pdf, path_light_pmf(sc, ps, sc->fp->env_light, 1) * env_pdf(sc->fp, &sc->env, ps->ray.d));
#endif
    ps->L += ps->beta * w * env_radiance(sc->fp, &sc->env, ps->ray.d);
#endif
}

/* The MIS weight of the emission the ray sees at s against light sampling at
 * the vertex the ray left: 1 where that vertex sampled no light (a delta
 * lobe, the camera, path-bsdf) or s is not in the light table. */
CLP_GPU_INLINE float path_emission_weight(const SceneData* sc, const PathState* ps, const Hit* h, const Surface* s) {
    float w = 1.0f;
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH && defined(CLP_HAS_TRIANGLE_LIGHTS)
    const uint li = s->tv->light;
    if (!ps->prev_delta && li != CLP_NO_LIGHT) {
        const float pdf = triangle_sample_pdf(&sc->lights[li], ps->prev_p, ps->ray.d, h->t);
        w = power_heuristic(ps->prev_pdf, path_light_pmf(sc, ps, li, 0) * pdf);
    }
#endif
    return w;
}

/* Whether the surface emits (its emission's MIS weight is wanted). */
static inline int surface_emits(const Surface* s) {
#ifdef CLP_HAS_EMISSION
    return max3(material_emission(surface_material(s), s->front)) > 0.0f;
#else
    return 0;
#endif
}

/* The emission of s times its MIS weight w joins the path's radiance. */
static inline void path_add_emission(PathState* ps, const Surface* s, float w) {
#ifdef CLP_HAS_EMISSION
    const float3 Le = material_emission(surface_material(s), s->front);
    if (max3(Le) > 0.0f) ps->L += ps->beta * w * Le;
#endif
}

/* Russian roulette at s, once its emission is added: 1 when the path scatters there. */
CLP_GPU_INLINE int path_survives(const SceneData* sc, PathState* ps, const Surface* s) {
    if (ps->depth >= CLP_MAX_DEPTH || !material_scatters(surface_material(s))) return 0;
    return russian_roulette(sc->fp, ps->depth, &ps->beta, &ps->rng);
}

/* path_roulette: adds the emission of the surface s the ray hit (MIS-weighted
 * against light sampling at the vertex the ray left) and plays Russian
 * roulette. Returns 1 when the path scatters at s, 0 when it has ended. (The
 * wavefront runs its parts apart: wf_shade.) */
CLP_GPU_INLINE int path_roulette(const SceneData* sc, PathState* ps, const Hit* h, const Surface* s) {
#ifdef CLP_HAS_EMISSION
    const float3 Le = material_emission(surface_material(s), s->front);
    if (max3(Le) > 0.0f) ps->L += ps->beta * path_emission_weight(sc, ps, h, s) * Le;
#endif
    return path_survives(sc, ps, s);
}

#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
/* Whether next-event estimation runs at s (it draws its numbers only then). */
static inline int path_wants_light(const SceneData* sc, const Surface* s) {
    return sc->fp->light_count > 0 && !material_is_delta(surface_material(s));
}

/* Next-event estimation's light sample from p (n: the normal the light BVH
 * weighs lights with), by the path's next three numbers u0, u1, u2: u0 picks
 * the light, by the light BVH or in proportion to power. Returns 0 when it
 * gives nothing. */
CLP_GPU_INLINE int path_light_sample(const SceneData* sc, float3 p, float3 n, float u0, float u1, float u2,
                                     LightSample* ls) {
#ifdef CLP_LIGHT_BVH
    float pmf = 0.0f;
    const uint li = light_bvh_sample(&sc->lbvh, p, n, u0, &pmf);
    if (li == CLP_NO_LIGHT) return 0;
#else
    const uint li = pick_light(sc->alias, sc->fp->light_count, u0);
    const float pmf = sc->alias[li].pmf;
#endif
    return sample_light(sc->lights, li, pmf, sc->fp, &sc->env, p, u1, u2, ls);
}

/* Next-event estimation at s, given the light sample (lit: path_light_sample's
 * answer), weighted against BSDF sampling of the same path by the power
 * heuristic (Veach 1997, ch. 9): returns the unoccluded contribution per unit
 * throughput, and *sh gets the shadow ray that decides it (inactive where
 * there is none). wo is the direction back along the path's ray. */
CLP_GPU_INLINE float3 path_light_eval(const Surface* s, float3 wo, const LightSample* ls, int lit, ShadowRay* sh) {
    sh->active = 0;
    if (!lit) return (float3)(0.0f);
    float bsdf_pdf;
    float3 f = material_eval(surface_material(s), s->ng, s->ns, wo, ls->wi, &bsdf_pdf surface_layers_arg(s));
    if (!(max3(f) > 0.0f) || !(max3(ls->L) > 0.0f)) return (float3)(0.0f);
    float3 o = offset_ray_origin(s->p, s->err, s->ng, ls->wi);
    sh->active = 1;
    sh->o = o;
    sh->d = ls->infinite ? ls->wi : ls->to - o;
    sh->tmax = ls->infinite ? INFINITY : 1.0f;
    float w = ls->delta ? 1.0f : power_heuristic(ls->pdf, bsdf_pdf);
    return f * ls->L * (w / ls->pdf);
}

/* The contribution v joins the path: through the shadow ray *sh when there is
 * one (path_shadow_done), else at once (zero). */
CLP_GPU_INLINE void path_light_join(PathState* ps, float3 v, ShadowRay* sh) {
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

/* Whether the ray a path scattering at a vertex of this depth would take
 * can add light. That ray reaches the deepest vertex (CLP_MAX_DEPTH), where
 * no light is sampled and the path ends, so all it can add is emission or the
 * environment: in a program with neither (a scene lit by point, spot or
 * directional lights alone) the path ends after the light sample instead,
 * with the same image and one ray fewer (Embree's `pathtracer` never traces
 * that ray). */
static inline int path_next_ray_gathers(uint depth) {
#if defined(CLP_HAS_EMISSION) || defined(CLP_HAS_ENV)
    return 1;
#else
    return depth + 1u < CLP_MAX_DEPTH;
#endif
}

/* The last phase: samples the BSDF at s (the path's next three numbers,
 * wo the direction back along its ray). Returns 0 when the path ends here. */
CLP_GPU_INLINE int path_scatter(Rng* rng, const Surface* s, float3 wo, BsdfSample* bs) {
    float u1 = rng_next(rng), u2 = rng_next(rng), u3 = rng_next(rng);
    return material_sample(surface_material(s), s->ng, s->ns, wo, u1, u2, u3, bs surface_layers_arg(s));
}

/* The path takes the sampled direction bs->wi: everything but where its
 * next ray starts (path_follow). */
CLP_GPU_INLINE void path_turn(PathState* ps, const BsdfSample* bs) {
    ps->beta *= bs->weight;
    ps->prev_pdf = bs->pdf;
    ps->prev_delta = bs->delta;
    ps->ray.d = bs->wi;
    ++ps->depth;
}

/* The path goes on along the sampled direction bs->wi from s. */
CLP_GPU_INLINE void path_follow(PathState* ps, const Surface* s, const BsdfSample* bs) {
    path_turn(ps, bs);
    ps->prev_p = s->p;
    ps->ray.o = offset_ray_origin(s->p, s->err, s->ng, bs->wi);
}

/* One bounce, every phase: returns 1 when the path goes on along ps->ray, 0
 * when it has ended. *sh is the shadow ray to resolve before the next step
 * (path_shadow_done). */
static inline int path_step(const SceneData* sc, PathState* ps, const Hit* h, ShadowRay* sh) {
    sh->active = 0;
    if (h->tri < 0) {
        path_miss(sc, ps);
        return 0;
    }
    Surface s;
    surface_at(&s, sc, h, ps->ray.d);
    if (!path_roulette(sc, ps, h, &s)) return 0;
#ifdef CLP_LIGHT_BVH
    const uint nq = lbvh_encode_normal(s.ng); /* the light BVH's normal here, as the wavefront keeps it */
    const float3 n = lbvh_octahedral(nq);
#else
    const float3 n = s.ng;
#endif
#if CLP_INTEGRATOR == CLP_INTEGRATOR_PATH
    if (path_wants_light(sc, &s)) {
        float u0 = rng_next(&ps->rng), u1 = rng_next(&ps->rng), u2 = rng_next(&ps->rng);
        LightSample ls;
        const int lit = path_light_sample(sc, s.p, n, u0, u1, u2, &ls);
        const float3 v = path_light_eval(&s, -ps->ray.d, &ls, lit, sh);
        path_light_join(ps, v, sh);
    }
#endif
    if (!path_next_ray_gathers(ps->depth)) return 0;
    BsdfSample bs;
    if (!path_scatter(&ps->rng, &s, -ps->ray.d, &bs)) return 0;
    path_follow(ps, &s, &bs);
#ifdef CLP_LIGHT_BVH
    ps->prev_n = nq;
#endif
    return 1;
}

/* The shadow ray's verdict: its contribution joins the path's radiance when
 * the light is unoccluded. */
static inline void path_shadow_done(float3* L, const ShadowRay* sh, int occluded_light) {
    if (!occluded_light) *L += sh->beta * sh->v;
}

#endif
#endif
