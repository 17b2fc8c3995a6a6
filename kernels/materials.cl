/* Materials: what a surface emits and how it scatters. Each kind has one
 * definition used both to sample a direction (material_sample) and to evaluate
 * a given one (material_eval), so the two cannot disagree. Kinds a scene does
 * not use are compiled out (CLP_HAS_MAT_*).
 *
 * Directions point away from the surface. BSDFs work in a local frame whose z
 * axis is the shading normal; `ng` is the geometric normal of the triangle's
 * winding (its front side). */
#ifndef CLP_MATERIALS_CL
#define CLP_MATERIALS_CL

#include "common.h"
#include "sampling.cl"
/* textures.cl defines CLP_MAT_SPACE: where the material functions read materials from. */
#include "textures.cl"
/* A material's float[3] as float3, from whichever address space it is in. */
#define CLP_M3(p) ((float3)((p)[0], (p)[1], (p)[2]))

/* ---- emission ---------------------------------------------------------- */

/* Radiance emitted towards a ray that hit the surface from the front
 * (front = the side the triangle's winding faces) or the back. */
static inline float3 material_emission(CLP_MAT_SPACE const Material* m, int front) {
    if (!front && !(m->flags & CLP_MATF_TWO_SIDED_EMISSION)) return (float3)(0.0f);
    return CLP_M3(m->emission);
}

static inline int material_scatters(CLP_MAT_SPACE const Material* m) {
    return m->kind != CLP_MAT_DIFFUSE || m->albedo[0] > 0.0f || m->albedo[1] > 0.0f || m->albedo[2] > 0.0f;
}

/* Roughness below this (alpha = roughness^2 < 1e-3) is treated as a perfectly
 * smooth surface: the GGX lobe would be narrower than float can represent. */
#define CLP_SMOOTH_ALPHA 1e-3f

static inline float ggx_alpha(CLP_MAT_SPACE const Material* m) { return m->roughness * m->roughness; }

/* Materials whose scattering is a Dirac delta: no light sampling, no MIS. */
static inline int material_is_delta(CLP_MAT_SPACE const Material* m) {
    switch (m->kind) {
#ifdef CLP_HAS_MAT_MIRROR
    case CLP_MAT_MIRROR: return 1;
#endif
#ifdef CLP_HAS_MAT_CONDUCTOR
    case CLP_MAT_CONDUCTOR: return ggx_alpha(m) < CLP_SMOOTH_ALPHA;
#endif
#ifdef CLP_HAS_MAT_DIELECTRIC
    case CLP_MAT_DIELECTRIC: return ggx_alpha(m) < CLP_SMOOTH_ALPHA;
#endif
    default: return 0;
    }
}

/* ---- frames and helpers ------------------------------------------------- */

typedef struct {
    float3 t, b, n;
} Frame;

static inline Frame frame_about(float3 n) {
    Frame f;
    f.n = n;
    make_frame(n, &f.t, &f.b);
    return f;
}
static inline float3 to_local(const Frame* f, float3 v) { return (float3)(dot(v, f->t), dot(v, f->b), dot(v, f->n)); }
static inline float3 from_local(const Frame* f, float3 v) { return v.x * f->t + v.y * f->b + v.z * f->n; }

static inline float3 schlick_fresnel(float3 f0, float cos_theta) {
    float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
    float m2 = m * m;
    return f0 + ((float3)(1.0f) - f0) * (m2 * m2 * m);
}

/* Unpolarised Fresnel reflectance of a dielectric interface. cos_i > 0 on the
 * side the light comes from; eta = n_transmitted / n_incident. 1 under total
 * internal reflection. (PBR 4th ed., 9.3.) */
static inline float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

/* ---- GGX (Trowbridge-Reitz) microfacets, isotropic ---------------------- */
/* Walter et al. 2007 for D and Smith's G; the height-correlated masking-
 * shadowing of Heitz 2014; visible-normal sampling of Heitz 2018. */

static inline float ggx_d(float3 h, float alpha) {
    float a2 = alpha * alpha;
    float c2 = h.z * h.z;
    float d = c2 * (a2 - 1.0f) + 1.0f;
    return a2 / (CLP_PI * d * d);
}

static inline float ggx_lambda(float3 w, float alpha) {
    float c2 = w.z * w.z;
    if (c2 <= 0.0f) return INFINITY;
    float tan2 = fmax(0.0f, 1.0f - c2) / c2;
    return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

static inline float ggx_g1(float3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
static inline float ggx_g2(float3 wo, float3 wi, float alpha) {
    return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

/* Normal visible from wo (wo.z > 0), distributed as D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z. */
static inline float3 ggx_sample_visible_normal(float3 wo, float alpha, float u1, float u2) {
    float3 vh = normalize3((float3)(alpha * wo.x, alpha * wo.y, wo.z));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    float3 t1 = len2 > 0.0f ? (float3)(-vh.y, vh.x, 0.0f) * rsqrt(len2) : (float3)(1.0f, 0.0f, 0.0f);
    float3 t2 = cross(vh, t1);
    float r = sqrt(u1);
    const float2 cs = cos_sin_pi(2.0f * u2); /* the angle in units of pi (sampling.cl) */
    float p1 = r * cs.x, p2 = r * cs.y;
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
    float3 nh = p1 * t1 + p2 * t2 + sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize3((float3)(alpha * nh.x, alpha * nh.y, fmax(1e-6f, nh.z)));
}

/* pdf of wi = reflect(wo, h) when h is a visible normal. */
static inline float ggx_reflection_pdf(float3 wo, float3 h, float alpha) {
    float wo_h = dot(wo, h);
    if (wo.z <= 0.0f || wo_h <= 0.0f) return 0.0f;
    return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}

/* ---- rough dielectric ---------------------------------------------------- */
/* Walter et al. 2007, "Microfacet Models for Refraction through Rough
 * Surfaces": reflection through the half vector, transmission through the
 * generalised half vector h ~ wo + eta wi, both from visible normals. Local
 * frame with wo above (wo.z > 0): the caller mirrors an inside wo below the
 * surface to above and passes eta = n_transmitted / n_incident for that side.
 * Returns f |cos theta_i| and the pdf of sampling wi (Fresnel picks between
 * the lobes); transmitted radiance is scaled by 1/eta^2 as for smooth glass. */
static inline float rough_dielectric_eval(float3 wo, float3 wi, float alpha, float eta, float* pdf) {
    *pdf = 0.0f;
    if (wo.z <= 0.0f || wi.z == 0.0f) return 0.0f;
    int reflect = wi.z > 0.0f;
    float3 h = reflect ? wo + wi : wo + eta * wi;
    if (!(dot(h, h) > 0.0f)) return 0.0f;
    h = normalize3(h);
    if (h.z < 0.0f) h = -h;
    float wo_h = dot(wo, h), wi_h = dot(wi, h);
    /* Back-facing microfacets: wo must see h, and wi must be on h's side for
     * reflection and beyond it for transmission. */
    if (wo_h <= 0.0f || (reflect ? wi_h <= 0.0f : wi_h >= 0.0f)) return 0.0f;
    float F = fresnel_dielectric(wo_h, eta);
    float d = ggx_d(h, alpha), g1 = ggx_g1(wo, alpha), g2 = ggx_g2(wo, wi, alpha);
    float visible = g1 * d / wo.z; /* D_wo(h) / (wo.h) */
    if (reflect) {
        *pdf = F * visible / 4.0f;
        return F * d * g2 / (4.0f * wo.z);
    }
    float denom = wo_h + eta * wi_h;
    float jacobian = eta * eta * fabs(wi_h) / (denom * denom); /* dh / dwi */
    *pdf = (1.0f - F) * visible * wo_h * jacobian;
    return (1.0f - F) * d * g2 * fabs(wi_h) * wo_h / (wo.z * denom * denom);
}

/* Samples wi for wo.z > 0 as rough_dielectric_eval describes; *weight is
 * f |cos| / pdf without the tint. Returns 0 when the sample fails. */
static inline int rough_dielectric_sample(float3 wo, float alpha, float eta, float u1, float u2, float u3, float3* wi,
                                   float* pdf, float* weight) {
    float3 h = ggx_sample_visible_normal(wo, alpha, u1, u2);
    float wo_h = dot(wo, h);
    if (wo_h <= 0.0f) return 0;
    float F = fresnel_dielectric(wo_h, eta);
    if (u3 < F) {
        *wi = 2.0f * wo_h * h - wo;
        if (wi->z <= 0.0f) return 0;
    } else {
        /* Snell's law about h (F < 1 here, so no total internal reflection). */
        float sin2_t = (1.0f - wo_h * wo_h) / (eta * eta);
        float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
        *wi = normalize3(-wo / eta + (wo_h / eta - cos_t) * h);
        if (wi->z >= 0.0f) return 0;
    }
    float f = rough_dielectric_eval(wo, *wi, alpha, eta, pdf);
    if (!(*pdf > 0.0f)) return 0;
    *weight = f / *pdf;
    return 1;
}

#ifdef CLP_HAS_MAT_GLTF
/* The glTF metallic-roughness material, in the local frame (material_gltf.cl). */
static float3 gltf_eval(CLP_MAT_SPACE const Material* m, float3 wo, float3 wi, float* pdf);
static int gltf_sample(CLP_MAT_SPACE const Material* m, float3 wo, float u1, float u2, float u3, float3* wi);
#endif

#ifdef CLP_GLTF_LAYERS
/* A glTF material's layers at one point, textures applied (surface_params.cl):
 * they travel beside the material, as the last argument of material_eval and
 * material_sample, only in programs compiled with them, so other programs'
 * BSDFs keep their arguments and registers. */
typedef struct {
    float3 coat_n;      /* the clear coat's normal (world; the interpolated normal unless the coat has a normal map) */
    float clearcoat;    /* coat weight in [0, 1]; 0: no coat */
    float coat_roughness;
    float transmission; /* share of the dielectric base's diffuse lobe that transmits, [0, 1] */
} GltfLayers;
#define CLP_LAYERS_PARAM , const GltfLayers* layers
#define CLP_LAYERS_ARG(l) , (l)
CLP_GPU_INLINE float3 gltf_layered_eval(CLP_MAT_SPACE const Material* m, float3 wo, float3 wi, const GltfLayers* l, float* pdf);
CLP_GPU_INLINE int gltf_layered_sample(CLP_MAT_SPACE const Material* m, float3 wo, const GltfLayers* l, float u1, float u2,
                               float u3, float3* wi);
#else
#define CLP_LAYERS_PARAM
#define CLP_LAYERS_ARG(l)
#endif

/* ---- the BSDF interface ------------------------------------------------- */

typedef struct {
    float3 wi;     /* sampled direction (world) */
    float3 weight; /* f |cos theta_i| / pdf; for deltas the whole throughput factor */
    float pdf;     /* solid-angle pdf; 0 for a delta lobe */
    int delta;
} BsdfSample;

/* The local frame for scattering at a surface seen from wo: reflective kinds
 * use the shading normal turned to wo's side of the geometric normal; glass
 * keeps the geometric orientation (front = outside) so entering and leaving
 * follow from the geometry, never from a flag carried along the path. */
static inline Frame scatter_frame(CLP_MAT_SPACE const Material* m, float3 ng, float3 ns, float3 wo) {
#ifdef CLP_HAS_MAT_DIELECTRIC
    if (m->kind == CLP_MAT_DIELECTRIC) {
        if (dot(ns, ng) < 0.0f) ns = -ns;
        return frame_about(ns);
    }
#endif
    float s = dot(wo, ng) >= 0.0f ? 1.0f : -1.0f;
    ng *= s;
    ns *= s;
    if (dot(ns, ng) < 0.0f) ns = ng; /* a shading normal facing away from the viewer is unusable */
    return frame_about(ns);
}

#ifdef CLP_GLTF_LAYERS
/* The layers in scatter_frame's local frame f: the coat normal turned to wo's
 * side of the geometric normal, as the shading normal is (a coat normal
 * facing away from the viewer is unusable: the geometric normal stands in). */
static inline GltfLayers gltf_layers_local(const GltfLayers* l, const Frame* f, float3 ng, float3 wo_w) {
    GltfLayers out = *l;
    float s = dot(wo_w, ng) >= 0.0f ? 1.0f : -1.0f;
    float3 nc = l->coat_n * s;
    if (dot(nc, ng * s) < 0.0f) nc = ng * s;
    out.coat_n = to_local(f, nc);
    return out;
}
#endif

/* f(wo, wi) |cos theta_i| and the pdf with which material_sample picks wi.
 * Delta lobes evaluate to 0. A reflection whose wi falls below the geometric
 * surface is 0: that light would have come through the triangle. */
static inline float3 material_eval(CLP_MAT_SPACE const Material* m, float3 ng, float3 ns, float3 wo_w, float3 wi_w,
                                   float* pdf CLP_LAYERS_PARAM) {
    *pdf = 0.0f;
    Frame f = scatter_frame(m, ng, ns, wo_w);
    float3 wo = to_local(&f, wo_w), wi = to_local(&f, wi_w);
#ifdef CLP_HAS_MAT_DIELECTRIC
    if (m->kind == CLP_MAT_DIELECTRIC) {
        float alpha = ggx_alpha(m);
        if (alpha < CLP_SMOOTH_ALPHA) return (float3)(0.0f);
        /* The lobe (reflection or transmission) must agree between the
         * shading frame and the geometry, as in material_sample. */
        if ((wi.z * wo.z > 0.0f) != (dot(wi_w, ng) * dot(wo_w, ng) > 0.0f)) return (float3)(0.0f);
        float eta = wo.z > 0.0f ? m->ior : 1.0f / m->ior;
        if (wo.z < 0.0f) { wo.z = -wo.z; wi.z = -wi.z; } /* mirror an inside wo above the surface */
        float fc = rough_dielectric_eval(wo, wi, alpha, eta, pdf);
        return wi.z < 0.0f ? CLP_M3(m->albedo) * fc : (float3)(fc);
    }
#endif
#ifdef CLP_GLTF_LAYERS
    if (m->kind == CLP_MAT_GLTF) {
        /* Transmission: the lobe (reflection or transmission) must agree
         * between the shading frame and the geometry, as for glass. */
        if ((wi.z > 0.0f) != (dot(wi_w, ng) * dot(wo_w, ng) > 0.0f)) return (float3)(0.0f);
        GltfLayers l = gltf_layers_local(layers, &f, ng, wo_w);
        return gltf_layered_eval(m, wo, wi, &l, pdf);
    }
#endif
    if (dot(wi_w, ng) * dot(wo_w, ng) <= 0.0f) return (float3)(0.0f); /* reflection only, below this line */
    if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
    switch (m->kind) {
#ifdef CLP_HAS_MAT_DIFFUSE
    case CLP_MAT_DIFFUSE:
        *pdf = diffuse_hemisphere_pdf(wi.z);
        return CLP_M3(m->albedo) * (wi.z * CLP_INV_PI);
#endif
#ifdef CLP_HAS_MAT_GLTF
    case CLP_MAT_GLTF: return gltf_eval(m, wo, wi, pdf);
#endif
#ifdef CLP_HAS_MAT_CONDUCTOR
    case CLP_MAT_CONDUCTOR: {
        float alpha = ggx_alpha(m);
        if (alpha < CLP_SMOOTH_ALPHA) return (float3)(0.0f);
        float3 h = normalize3(wo + wi);
        *pdf = ggx_reflection_pdf(wo, h, alpha);
        float3 F = schlick_fresnel(CLP_M3(m->albedo), dot(wo, h));
        return F * (ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z));
    }
#endif
    default: return (float3)(0.0f);
    }
}

/* Samples wi for wo with the numbers u1..u3. Returns 0 when the path ends here. */
static inline int material_sample(CLP_MAT_SPACE const Material* m, float3 ng, float3 ns, float3 wo_w, float u1, float u2, float u3,
                           BsdfSample* s CLP_LAYERS_PARAM) {
    Frame f = scatter_frame(m, ng, ns, wo_w);
    float3 wo = to_local(&f, wo_w);
    s->delta = 0;
    s->pdf = 0.0f;
    switch (m->kind) {
#ifdef CLP_HAS_MAT_DIFFUSE
    case CLP_MAT_DIFFUSE: {
        float3 wi = sample_diffuse_hemisphere(u1, u2);
        s->wi = from_local(&f, wi);
        s->pdf = diffuse_hemisphere_pdf(wi.z);
#ifdef CLP_UNIFORM_HEMISPHERE
        /* f cos / pdf = (albedo / pi) cos theta * 2 pi. */
        s->weight = CLP_M3(m->albedo) * (2.0f * wi.z);
#else
        /* Lambert sampled by cos theta / pi: the weight is the albedo exactly. */
        s->weight = CLP_M3(m->albedo);
#endif
        break;
    }
#endif
#ifdef CLP_HAS_MAT_MIRROR
    case CLP_MAT_MIRROR:
        s->wi = from_local(&f, (float3)(-wo.x, -wo.y, wo.z));
        s->weight = CLP_M3(m->albedo);
        s->delta = 1;
        break;
#endif
#ifdef CLP_HAS_MAT_CONDUCTOR
    case CLP_MAT_CONDUCTOR: {
        float alpha = ggx_alpha(m);
        if (wo.z <= 0.0f) return 0;
        if (alpha < CLP_SMOOTH_ALPHA) {
            s->wi = from_local(&f, (float3)(-wo.x, -wo.y, wo.z));
            s->weight = schlick_fresnel(CLP_M3(m->albedo), wo.z);
            s->delta = 1;
            break;
        }
        float3 h = ggx_sample_visible_normal(wo, alpha, u1, u2);
        float3 wi = 2.0f * dot(wo, h) * h - wo;
        if (wi.z <= 0.0f) return 0;
        s->wi = from_local(&f, wi);
        s->pdf = ggx_reflection_pdf(wo, h, alpha);
        /* f cos / pdf = F G2 / G1(wo) for visible-normal sampling. */
        s->weight = schlick_fresnel(CLP_M3(m->albedo), dot(wo, h)) * (ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha));
        break;
    }
#endif
#ifdef CLP_HAS_MAT_GLTF
    case CLP_MAT_GLTF: {
        /* One definition: the sampled direction's value and pdf come from gltf_eval. */
        float3 wi;
#ifdef CLP_GLTF_LAYERS
        GltfLayers l = gltf_layers_local(layers, &f, ng, wo_w);
        if (!gltf_layered_sample(m, wo, &l, u1, u2, u3, &wi)) return 0;
        float3 val = gltf_layered_eval(m, wo, wi, &l, &s->pdf);
        if (!(s->pdf > 0.0f)) return 0;
        s->wi = from_local(&f, wi);
        s->weight = val / s->pdf;
        /* Reflection must stay on wo's side of the triangle, transmission cross it. */
        return (dot(s->wi, ng) * dot(wo_w, ng) > 0.0f) == (wi.z > 0.0f);
#else
        if (!gltf_sample(m, wo, u1, u2, u3, &wi)) return 0;
        float3 val = gltf_eval(m, wo, wi, &s->pdf);
        if (!(s->pdf > 0.0f)) return 0;
        s->wi = from_local(&f, wi);
        s->weight = val / s->pdf;
        break;
#endif
    }
#endif
#ifdef CLP_HAS_MAT_DIELECTRIC
    case CLP_MAT_DIELECTRIC: {
        /* wo.z > 0: wo is outside (the front of the winding). */
        int outside = wo.z > 0.0f;
        float eta = outside ? m->ior : 1.0f / m->ior; /* n_transmitted / n_incident for light along -wi */
        float alpha = ggx_alpha(m);
        if (alpha >= CLP_SMOOTH_ALPHA) {
            float3 wm = (float3)(wo.x, wo.y, fabs(wo.z)), wi;
            float weight;
            if (!rough_dielectric_sample(wm, alpha, eta, u1, u2, u3, &wi, &s->pdf, &weight)) return 0;
            if (!outside) wi.z = -wi.z;
            s->wi = from_local(&f, wi);
            s->weight = wi.z * wo.z < 0.0f ? CLP_M3(m->albedo) * weight : (float3)(weight);
            /* Reflection must stay on wo's side of the triangle, transmission cross it. */
            return (dot(s->wi, ng) * dot(wo_w, ng) > 0.0f) == (wi.z * wo.z > 0.0f);
        }
        /* Smooth glass. */
        float cos_o = fabs(wo.z);
        float F = fresnel_dielectric(cos_o, eta);
        s->delta = 1;
        if (u3 < F) {
            s->wi = from_local(&f, (float3)(-wo.x, -wo.y, wo.z));
            s->weight = (float3)(1.0f);
        } else {
            float sin2_t = (1.0f - cos_o * cos_o) / (eta * eta);
            float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
            float3 wi = (float3)(-wo.x / eta, -wo.y / eta, outside ? -cos_t : cos_t);
            s->wi = from_local(&f, normalize3(wi));
            /* Radiance is compressed into the denser medium: scale by 1/eta^2
             * (PBR 4th ed., 9.5.2). The tint colours transmitted light only. */
            s->weight = CLP_M3(m->albedo) / (eta * eta);
        }
        /* The sampled side must agree with the geometry, or the path would
         * slip through the triangle. */
        if (dot(s->wi, ng) * dot(wo_w, ng) > 0.0f ? u3 >= F : u3 < F) return 0;
        return 1;
    }
#endif
    default: return 0;
    }
    /* A reflection that points below the geometric surface ends the path. */
    return dot(s->wi, ng) * dot(wo_w, ng) > 0.0f;
}

/* What the albedo debug view shows. */
static inline float3 material_albedo(CLP_MAT_SPACE const Material* m) { return CLP_M3(m->albedo); }

/* The glTF material's definitions need the GGX functions above. */
#include "material_gltf.cl"

#endif
