/* Materials: what a surface emits and how it scatters. Each kind has one
 * definition used both to sample a direction and to weight it. */

/* Radiance emitted towards a ray that hit the surface from the front
 * (front = the side the triangle's winding faces) or the back. */
inline float3 material_emission(global const Material* m, int front) {
    if (!front && !(m->flags & CLP_MATF_TWO_SIDED_EMISSION)) return (float3)(0.0f);
    return load3g(m->emission);
}

/* Samples an outgoing direction about the shading normal n (facing the
 * incoming side). Returns the throughput weight f cos / pdf. Lambert sampled by
 * cos theta / pi: the weight is the albedo exactly. */
inline float3 material_sample(global const Material* m, float3 n, float u1, float u2, float3* wi) {
    *wi = to_world(sample_cosine_hemisphere(u1, u2), n);
    return load3g(m->albedo);
}

inline int material_scatters(global const Material* m) {
    return m->albedo[0] > 0.0f || m->albedo[1] > 0.0f || m->albedo[2] > 0.0f;
}
