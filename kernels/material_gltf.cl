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

#endif

#endif
