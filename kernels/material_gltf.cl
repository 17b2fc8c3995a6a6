/* The glTF 2.0 metallic-roughness material (CLP_MAT_GLTF), after the
 * specification's appendix B: a GGX conductor tinted by the base colour
 * (Schlick Fresnel, F0 = base colour) mixed by `metallic` with a dielectric:
 * a GGX specular layer (Schlick Fresnel, F0 from the ior, 0.04 for 1.5) over a
 * Lambertian base.
 *
 * One deliberate change: the appendix weights the diffuse base by
 * 1 - F(v.h), which creates energy at grazing angles (a white rough-0 surface
 * seen at 1 degree reflects about 1.9 times what arrives: the specular layer
 * already returns F(n.v) of it, and the base adds nearly all of it again).
 * The base here is weighted by (1 - F(n.wo)) (1 - F(n.wi)), the coupling of
 * Ashikhmin and Shirley (2000): reciprocal, and it never reflects more than
 * arrives (tests/kernels/gltf_material_test.cpp, white furnace).
 *
 * GGX alpha is roughness^2 as in glTF, kept at least CLP_SMOOTH_ALPHA so the
 * material is never a Dirac delta (next-event estimation always applies).
 * Sampling picks the specular lobe (visible normals, Heitz 2018) or the
 * cosine-weighted base with probabilities from their albedo estimates at wo;
 * the pdf is the mixture's, which makes the estimator one-sample MIS over
 * the two lobes. Frames: local, shading normal +z, wo.z > 0 and wi.z > 0. */

#ifndef CLP_MATERIAL_GLTF_CL
#define CLP_MATERIAL_GLTF_CL

#include "materials.cl"

#ifdef CLP_HAS_MAT_GLTF

static inline float gltf_alpha(CLP_MAT_SPACE const Material* m) { return fmax(m->roughness * m->roughness, CLP_SMOOTH_ALPHA); }

/* Reflectance at normal incidence of the dielectric layer. */
static inline float gltf_f0(CLP_MAT_SPACE const Material* m) {
    float r = (m->ior - 1.0f) / (m->ior + 1.0f);
    return r * r;
}

static inline float schlick1(float f0, float c) {
    float x = clamp(1.0f - c, 0.0f, 1.0f);
    float x2 = x * x;
    return f0 + (1.0f - f0) * x2 * x2 * x;
}

static inline float gltf_luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* Probability of sampling the specular lobe for this wo. */
static inline float gltf_specular_probability(CLP_MAT_SPACE const Material* m, float3 wo) {
    float3 base = CLP_M3(m->albedo);
    float metal = clamp(m->metallic, 0.0f, 1.0f);
    float fd = schlick1(gltf_f0(m), wo.z);
    float spec = metal * gltf_luminance(schlick_fresnel(base, wo.z)) + (1.0f - metal) * fd;
    float diff = (1.0f - metal) * (1.0f - fd) * gltf_luminance(base);
    return spec + diff > 0.0f ? spec / (spec + diff) : 1.0f;
}

static float3 gltf_eval(CLP_MAT_SPACE const Material* m, float3 wo, float3 wi, float* pdf) {
    *pdf = 0.0f;
    if (wo.z <= 0.0f || wi.z <= 0.0f) return (float3)(0.0f);
    float alpha = gltf_alpha(m);
    float3 base = CLP_M3(m->albedo);
    float metal = clamp(m->metallic, 0.0f, 1.0f);
    float f0 = gltf_f0(m);
    float3 h = normalize3(wo + wi);
    float wo_h = dot(wo, h);
    /* Specular: D G2 / (4 cos_o cos_i), times cos_i. */
    float spec = ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z);
    float3 f_metal = schlick_fresnel(base, wo_h) * spec;
    float f_coat = schlick1(f0, wo_h) * spec;
    float3 f_base = base * ((1.0f - schlick1(f0, wo.z)) * (1.0f - schlick1(f0, wi.z)) * CLP_INV_PI * wi.z);
    float ps = gltf_specular_probability(m, wo);
    *pdf = ps * ggx_reflection_pdf(wo, h, alpha) + (1.0f - ps) * wi.z * CLP_INV_PI;
    return metal * f_metal + (1.0f - metal) * (f_base + (float3)(f_coat));
}

static int gltf_sample(CLP_MAT_SPACE const Material* m, float3 wo, float u1, float u2, float u3, float3* wi) {
    if (wo.z <= 0.0f) return 0;
    if (u3 < gltf_specular_probability(m, wo)) {
        float3 h = ggx_sample_visible_normal(wo, gltf_alpha(m), u1, u2);
        *wi = 2.0f * dot(wo, h) * h - wo;
    } else {
        *wi = sample_cosine_hemisphere(u1, u2);
    }
    return wi->z > 0.0f;
}

#ifdef CLP_GLTF_LAYERS
/* ---- the layers: KHR_materials_clearcoat and KHR_materials_transmission ----
 *
 * Clear coat (the extension's fresnel_coat): a GGX dielectric layer, ior 1.5
 * (F0 0.04), of its own roughness and normal, over the material:
 *   f = c F(wo.h_c) D_c G2_c / (4 |wo.n_c| |wi.n_c|)
 *     + (1 - c F(wo.n_c)) (1 - c F(wi.n_c)) f_material.
 * The specification weights the material by 1 - c F(wo.n_c) alone and the
 * coat by c F(wo.n_c); the coat's Fresnel at the microfacet and the base's
 * attenuation on both ways make the sum reciprocal, as for the core
 * material's base (see the top of this file); for a smooth coat they are the
 * specification's.
 *
 * Transmission (thin-walled, the extension's model without
 * KHR_materials_volume): a share t of the dielectric base's diffuse lobe is
 * replaced by a GGX transmission lobe tinted by the base colour, with the
 * dielectric layer's roughness. The wall is infinitely thin, so the ray
 * refracts in and back out at once and leaves unbent: the lobe is the
 * reflection lobe mirrored through the surface (wi -> (wi.x, wi.y, -wi.z)),
 * about the straight-through direction -wo, weighted like the diffuse base by
 * (1 - F(wo.z)) (1 - F(|wi.z|)), once for each interface it crosses.
 *
 * Sampling picks one of coat, specular, diffuse and transmission with
 * probabilities from their albedo estimates at wo; the pdf is the mixture's. */

#define CLP_COAT_F0 0.04f

static inline float gltf_coat_alpha(const GltfLayers* l) {
    return fmax(l->coat_roughness * l->coat_roughness, CLP_SMOOTH_ALPHA);
}

/* Lobe probabilities at wo: coat, specular, diffuse, transmission. */
static inline float4 gltf_layer_probabilities(CLP_MAT_SPACE const Material* m, const GltfLayers* l, float3 wo) {
    float3 base = CLP_M3(m->albedo);
    float metal = clamp(m->metallic, 0.0f, 1.0f);
    float co = dot(wo, l->coat_n);
    float coat = co > 0.0f ? l->clearcoat * schlick1(CLP_COAT_F0, co) : 0.0f;
    float under = 1.0f - l->clearcoat * schlick1(CLP_COAT_F0, fabs(co));
    float fd = schlick1(gltf_f0(m), wo.z);
    float spec = under * (metal * gltf_luminance(schlick_fresnel(base, wo.z)) + (1.0f - metal) * fd);
    float body = under * (1.0f - metal) * (1.0f - fd) * gltf_luminance(base);
#ifdef CLP_HAS_TRANSMISSION
    float t = l->transmission;
#else
    float t = 0.0f;
#endif
    float sum = coat + spec + body;
    if (!(sum > 0.0f)) return (float4)(0.0f, 1.0f, 0.0f, 0.0f);
    return (float4)(coat, spec, body * (1.0f - t), body * t) / sum;
}

CLP_GPU_INLINE float3 gltf_layered_eval(CLP_MAT_SPACE const Material* m, float3 wo, float3 wi, const GltfLayers* l, float* pdf) {
    *pdf = 0.0f;
    if (wo.z <= 0.0f || wi.z == 0.0f) return (float3)(0.0f);
    float alpha = gltf_alpha(m);
    float3 base = CLP_M3(m->albedo);
    float metal = clamp(m->metallic, 0.0f, 1.0f);
    float f0 = gltf_f0(m);
    float4 p = gltf_layer_probabilities(m, l, wo);
    float co = dot(wo, l->coat_n), ci = dot(wi, l->coat_n);
    float under = (1.0f - l->clearcoat * schlick1(CLP_COAT_F0, fabs(co))) * (1.0f - l->clearcoat * schlick1(CLP_COAT_F0, fabs(ci)));
    /* The dielectric base's share that goes into the body: diffuse or transmitted. */
    float body = (1.0f - metal) * (1.0f - schlick1(f0, wo.z)) * (1.0f - schlick1(f0, fabs(wi.z)));
#ifdef CLP_HAS_TRANSMISSION
    float t = l->transmission;
    if (wi.z < 0.0f) {
        float3 wr = (float3)(wi.x, wi.y, -wi.z);
        float3 h = normalize3(wo + wr);
        float lobe = ggx_d(h, alpha) * ggx_g2(wo, wr, alpha) / (4.0f * wo.z);
        *pdf = p.w * ggx_reflection_pdf(wo, h, alpha);
        return base * (under * body * t * lobe);
    }
#else
    float t = 0.0f;
    if (wi.z < 0.0f) return (float3)(0.0f);
#endif
    float3 h = normalize3(wo + wi);
    float wo_h = dot(wo, h);
    float spec = ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z);
    float3 f_metal = schlick_fresnel(base, wo_h) * spec;
    float f_spec = schlick1(f0, wo_h) * spec;
    float3 f = under * (metal * f_metal + (float3)((1.0f - metal) * f_spec) + base * (body * (1.0f - t) * CLP_INV_PI * wi.z));
    *pdf = p.y * ggx_reflection_pdf(wo, h, alpha) + p.z * wi.z * CLP_INV_PI;
    if (l->clearcoat > 0.0f && co > 0.0f && ci > 0.0f) {
        /* The coat's lobe in a frame about its normal. */
        Frame cf = frame_about(l->coat_n);
        float3 woc = to_local(&cf, wo), wic = to_local(&cf, wi);
        float3 hc = normalize3(woc + wic);
        float ac = gltf_coat_alpha(l);
        float coat = ggx_d(hc, ac) * ggx_g2(woc, wic, ac) / (4.0f * woc.z * wic.z) * wi.z;
        f += (float3)(l->clearcoat * schlick1(CLP_COAT_F0, dot(woc, hc)) * coat);
        *pdf += p.x * ggx_reflection_pdf(woc, hc, ac);
    }
    return f;
}

CLP_GPU_INLINE int gltf_layered_sample(CLP_MAT_SPACE const Material* m, float3 wo, const GltfLayers* l, float u1, float u2,
                               float u3, float3* wi) {
    if (wo.z <= 0.0f) return 0;
    float4 p = gltf_layer_probabilities(m, l, wo);
    if (u3 < p.x) {
        Frame cf = frame_about(l->coat_n);
        float3 woc = to_local(&cf, wo);
        float3 h = ggx_sample_visible_normal(woc, gltf_coat_alpha(l), u1, u2);
        *wi = from_local(&cf, 2.0f * dot(woc, h) * h - woc);
        return wi->z > 0.0f;
    }
    if (u3 < p.x + p.y) {
        float3 h = ggx_sample_visible_normal(wo, gltf_alpha(m), u1, u2);
        *wi = 2.0f * dot(wo, h) * h - wo;
        return wi->z > 0.0f;
    }
    if (u3 < p.x + p.y + p.z) {
        *wi = sample_cosine_hemisphere(u1, u2);
        return wi->z > 0.0f;
    }
#ifdef CLP_HAS_TRANSMISSION
    /* Transmission: the mirrored reflection lobe (see above). */
    float3 h = ggx_sample_visible_normal(wo, gltf_alpha(m), u1, u2);
    float3 wr = 2.0f * dot(wo, h) * h - wo;
    *wi = (float3)(wr.x, wr.y, -wr.z);
    return wi->z < 0.0f;
#else
    return 0;
#endif
}
#endif

#endif

#endif
