/* Sampling directions and building frames. */

#define CLP_PI 3.14159265358979323846f
#define CLP_INV_PI 0.31830988618379067154f

/* Orthonormal basis around a unit vector n, without the singularity of the
 * cross-product method: Duff et al. 2017, "Building an Orthonormal Basis, Revisited". */
inline void make_frame(float3 n, float3* t, float3* b) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    *t = (float3)(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    *b = (float3)(c, s + n.y * n.y * a, -n.y);
}

/* Uniform point on the unit disk by Shirley & Chiu's (1997) concentric map,
 * which keeps strata compact (less distortion than the polar map). */
inline float2 sample_concentric_disk(float u1, float u2) {
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f) return (float2)(0.0f, 0.0f);
    float r, phi;
    if (fabs(a) > fabs(b)) {
        r = a;
        phi = (CLP_PI / 4.0f) * (b / a);
    } else {
        r = b;
        phi = (CLP_PI / 2.0f) - (CLP_PI / 4.0f) * (a / b);
    }
    return (float2)(r * cos(phi), r * sin(phi));
}

/* Cosine-weighted direction about +z (Malley's method: lift a uniform disk
 * point to the hemisphere). pdf = cos(theta) / pi. */
inline float3 sample_cosine_hemisphere(float u1, float u2) {
    float2 d = sample_concentric_disk(u1, u2);
    float z = sqrt(fmax(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return (float3)(d.x, d.y, z);
}

inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * CLP_INV_PI : 0.0f; }

/* Uniform direction on the hemisphere about +z. pdf = 1 / (2 pi). */
inline float3 sample_uniform_hemisphere(float u1, float u2) {
    float z = u1;
    float r = sqrt(fmax(0.0f, 1.0f - z * z));
    float phi = 2.0f * CLP_PI * u2;
    return (float3)(r * cos(phi), r * sin(phi), z);
}

inline float uniform_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? 0.5f * CLP_INV_PI : 0.0f; }

/* The direction a diffuse bounce takes about +z, and its pdf: cosine-weighted
 * by default; uniform with -DCLP_UNIFORM_HEMISPHERE (the thesis text's choice,
 * kept so that the convergence benchmark can measure what cosine weighting
 * gains). Sample and pdf are chosen together here, so they cannot disagree. */
inline float3 sample_diffuse_hemisphere(float u1, float u2) {
#ifdef CLP_UNIFORM_HEMISPHERE
    return sample_uniform_hemisphere(u1, u2);
#else
    return sample_cosine_hemisphere(u1, u2);
#endif
}

inline float diffuse_hemisphere_pdf(float cos_theta) {
#ifdef CLP_UNIFORM_HEMISPHERE
    return uniform_hemisphere_pdf(cos_theta);
#else
    return cosine_hemisphere_pdf(cos_theta);
#endif
}

inline float3 to_world(float3 v, float3 n) {
    float3 t, b;
    make_frame(n, &t, &b);
    return v.x * t + v.y * b + v.z * n;
}
