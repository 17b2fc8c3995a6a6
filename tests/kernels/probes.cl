/* Test-only entry points: each exposes one kernel function to the host tests,
 * so the tests exercise the very code the renderer runs. */
#ifndef CLP_PROBES_CL
#define CLP_PROBES_CL

#include "integrator.cl"
#include "light_bvh.cl"
#include "shared_struct_fields.h"

/* The layout the device compiler gives the shared structs: for each struct
 * (shared_struct_fields.h order) its size, then for each field its offset
 * and size. offsetof is not in every OpenCL C version: the address of the
 * field in a struct at address 0 is the same number. */
#define CLP_PROBE_OFFSETOF(S, f) ((uint)(size_t) & (((S*)0)->f))
#define CLP_PROBE_STRUCT(S) out[n++] = (uint)sizeof(S);
#define CLP_PROBE_FIELD(S, f) out[n] = CLP_PROBE_OFFSETOF(S, f), out[n + 1] = (uint)sizeof(((S*)0)->f), n += 2;
kernel void probe_struct_layout(global uint* out) {
    uint n = 0;
    CLP_SHARED_STRUCTS(CLP_PROBE_STRUCT)
    CLP_SHARED_FIELDS(CLP_PROBE_FIELD)
}

/* The host/kernel contracts of shared_structs.h as the kernels see them,
 * after every kernel file: ints first, then floats (contracts_test.cpp). */
kernel void probe_contracts(global uint* out, global float* fout) {
    out[0] = CLP_TILE;
    out[1] = CLP_BATCH_TILE;
    out[2] = CLP_BATCH_GRID;
    out[3] = CLP_BATCH_SAMPLES;
    out[4] = CLP_ENV_ROW_CDF(7u, 5u, 3u);
    out[5] = CLP_ENV_CDF_SIZE(7u, 5u);
    out[6] = CLP_ENV_IS_SAMPLED(CLP_ENV_NOT_SAMPLED);
    out[7] = CLP_ENV_IS_SAMPLED(0.0f);
    fout[0] = CLP_MIN_SPHERICAL_AREA;
    fout[1] = CLP_MAX_SPHERICAL_AREA;
    fout[2] = CLP_MIN_SPHERICAL_ELEVATION;
    fout[3] = CLP_ENV_NOT_SAMPLED;
    fout[4] = CLP_MIN_SPHERICAL_SPREAD;
}

/* Directions drawn from the environment distribution the host built, and
 * the pdf the kernels give them: out[i] = (d, solid-angle pdf). fp holds the
 * image size, scale and rotation as the renderer sets them. */
kernel void probe_env_sample(constant const FrameParams* fp, global const float4* pixels, global const float* cdf,
                             uint count, uint seed, global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    EnvMap env;
    env.pixels = pixels;
    env.cdf = cdf;
    Rng r = rng_seed(i, 3, seed);
    float u1 = rng_next(&r), u2 = rng_next(&r);
    float3 d = env_sample_direction(fp, &env, u1, u2);
    out[i] = (float4)(d, env_pdf(fp, &env, d));
}

/* out[i * n + j]: the j-th number of stream (pixel = i, sample = sample). */
kernel void probe_rng_stream(global float* out, uint count, uint n, uint sample, uint seed) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, sample, seed);
    for (uint j = 0; j < n; ++j) out[i * n + j] = rng_next(&r);
}

/* out[s * pixels + p]: the first number of stream (pixel p, sample s). */
kernel void probe_rng_first(global float* out, uint pixels, uint samples, uint seed) {
    uint i = get_global_id(0);
    if (i >= pixels * samples) return;
    Rng r = rng_seed(i % pixels, i / pixels, seed);
    out[i] = rng_next(&r);
}

/* Cosine-weighted directions about +z from the generator's own numbers. */
kernel void probe_cosine(global float* out, uint count, uint seed) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, 0, seed);
    float u1 = rng_next(&r), u2 = rng_next(&r);
    float3 d = sample_cosine_hemisphere(u1, u2);
    out[3 * i] = d.x;
    out[3 * i + 1] = d.y;
    out[3 * i + 2] = d.z;
}

/* cos_sin_pi (sampling.cl) of x[i] and, as the control's wrong answer, the
 * quarter-interval polynomials applied to x[i] unreduced. */
kernel void probe_cos_sin_pi(global const float* x, global float2* out, global float2* unreduced, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    out[i] = cos_sin_pi(x[i]);
    unreduced[i] = cos_sin_pi_quarter(x[i]);
}

/* length3 and normalize3 (common.h) of v[i] beside the builtins, and, as the
 * control's wrong answer, sqrt(dot(v, v)) with no fallback. */
kernel void probe_length3(global const float* v, global float* len, global float* len_builtin, global float* unit,
                          global float* unit_builtin, global float* unguarded, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float3 x = load3g(v + 3 * i);
    len[i] = length3(x);
    len_builtin[i] = length(x);
    vstore3(normalize3(x), i, unit);
    vstore3(normalize(x), i, unit_builtin);
    unguarded[i] = sqrt(dot(x, x));
}

/* atan2_upper(y[i], x[i]) (sampling.cl) and, as the control's wrong answer,
 * atan(y/x) without the quadrant rule. */
kernel void probe_atan2_upper(global const float* y, global const float* x, global float* out,
                              global float* naive, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    out[i] = atan2_upper(y[i], x[i]);
    naive[i] = atan(y[i] / x[i]);
}

/* Directions from a unit normal n[i] through the same frame code the materials use. */
kernel void probe_cosine_about(global const float* normals, global float* out, uint count, uint seed) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, 1, seed);
    float u1 = rng_next(&r), u2 = rng_next(&r);
    float3 n = load3g(normals + 3 * i);
    float3 d = to_world(sample_cosine_hemisphere(u1, u2), n);
    out[3 * i] = d.x;
    out[3 * i + 1] = d.y;
    out[3 * i + 2] = d.z;
}

/* Ray i (origin, direction: 6 floats) against triangle i (9 floats).
 * out[4i..]: hit flag, t, b1, b2. */
kernel void probe_triangle(global const float* rays, global const float* tris, global float* out, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    RayPre r = ray_prepare(load3g(rays + 6 * i), load3g(rays + 6 * i + 3));
    float t = 0.0f, b1 = 0.0f, b2 = 0.0f;
    int hit = intersect_triangle(&r, load3g(tris + 9 * i), load3g(tris + 9 * i + 3), load3g(tris + 9 * i + 6),
                                 INFINITY, &t, &b1, &b2);
    out[4 * i] = (float)hit;
    out[4 * i + 1] = t;
    out[4 * i + 2] = b1;
    out[4 * i + 3] = b2;
}

/* Ray i against the BVH: closest hit (t, original triangle index or -1) and
 * whether any hit exists before tmax[i]. */
kernel void probe_trace(global const AccelNode* nodes, global const TriVerts* tris, global const float* rays,
                        global const float* tmax, global float* out_t, global int* out_prim, global int* out_any,
                        uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    RayPre r = ray_prepare(load3g(rays + 6 * i), load3g(rays + 6 * i + 3));
    Hit h, a;
    traverse_bvh(&h, nodes, tris, &r, tmax[i], 0, 0);
    out_t[i] = h.t;
    out_prim[i] = h.tri >= 0 ? (int)tris[h.tri].prim : -1;
    traverse_bvh(&a, nodes, tris, &r, tmax[i], 1, 0);
    out_any[i] = a.tri >= 0;
}

/* Ray i against every triangle, no BVH: the reference for traversal tests.
 * Same hit rule as traversal: the closest t, the first triangle on ties. */
kernel void probe_brute(global const TriVerts* tris, uint tri_count, global const float* rays, global float* out_t,
                        global int* out_prim, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    RayPre r = ray_prepare(load3g(rays + 6 * i), load3g(rays + 6 * i + 3));
    Hit h;
    h.t = INFINITY;
    h.tri = -1;
    leaf_hits(&r, tris, 0, tri_count, &h, 0);
    out_t[i] = h.t;
    out_prim[i] = h.tri >= 0 ? (int)tris[h.tri].prim : -1;
}

/* Samples material m for the fixed direction wo in a frame where the geometric
 * and shading normals are both +z. wi_pdf: (wi, pdf), pdf -1 when the sample
 * ended the path; weight: (f cos / pdf, delta). */
#ifdef CLP_GLTF_LAYERS
/* Programs with the glTF layers: the plain probes pass none (no coat, no
 * transmission), probe_layered_* the ones given, in the frame of normal +z. */
static inline GltfLayers probe_layers(float4 p, float4 coat_n) {
    GltfLayers l;
    l.clearcoat = p.x;
    l.coat_roughness = p.y;
    l.transmission = p.z;
    l.coat_n = normalize(coat_n.xyz);
    return l;
}
#define CLP_PROBE_NO_LAYERS , &no_layers
#define CLP_PROBE_DECLARE_NO_LAYERS GltfLayers no_layers = probe_layers((float4)(0.0f), (float4)(0.0f, 0.0f, 1.0f, 0.0f));

kernel void probe_layered_sample(global const Material* m, float4 layers, float4 coat_n, float wox, float woy, float woz,
                                 uint count, uint seed, global float4* wi_pdf, global float4* weight) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, 0, seed);
    float3 n = (float3)(0.0f, 0.0f, 1.0f);
    float u1 = rng_next(&r), u2 = rng_next(&r), u3 = rng_next(&r);
    BsdfSample s;
    Material mp = *m;
    GltfLayers l = probe_layers(layers, coat_n);
    int ok = material_sample(&mp, n, n, (float3)(wox, woy, woz), u1, u2, u3, &s, &l);
    wi_pdf[i] = ok ? (float4)(s.wi, s.pdf) : (float4)(0.0f, 0.0f, 0.0f, -1.0f);
    weight[i] = ok ? (float4)(s.weight, (float)s.delta) : (float4)(0.0f);
}

kernel void probe_layered_eval(global const Material* m, float4 layers, float4 coat_n, uint count, global const float4* wo,
                               global const float4* wi, global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float3 n = (float3)(0.0f, 0.0f, 1.0f);
    float pdf;
    Material mp = *m;
    GltfLayers l = probe_layers(layers, coat_n);
    float3 f = material_eval(&mp, n, n, wo[i].xyz, wi[i].xyz, &pdf, &l);
    out[i] = (float4)(f, pdf);
}
#else
#define CLP_PROBE_NO_LAYERS
#define CLP_PROBE_DECLARE_NO_LAYERS
#endif

kernel void probe_bsdf_sample(global const Material* m, float wox, float woy, float woz, uint count, uint seed,
                              global float4* wi_pdf, global float4* weight) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, 0, seed);
    float3 n = (float3)(0.0f, 0.0f, 1.0f);
    float u1 = rng_next(&r), u2 = rng_next(&r), u3 = rng_next(&r);
    BsdfSample s;
    CLP_PROBE_DECLARE_NO_LAYERS
#ifdef CLP_SURFACE_PARAMS
    Material mp = *m; /* materials are private copies in programs with textures (textures.cl) */
    int ok = material_sample(&mp, n, n, (float3)(wox, woy, woz), u1, u2, u3, &s CLP_PROBE_NO_LAYERS);
#else
    int ok = material_sample(m, n, n, (float3)(wox, woy, woz), u1, u2, u3, &s);
#endif
    wi_pdf[i] = ok ? (float4)(s.wi, s.pdf) : (float4)(0.0f, 0.0f, 0.0f, -1.0f);
    weight[i] = ok ? (float4)(s.weight, (float)s.delta) : (float4)(0.0f);
}

/* out[i] = (f(wo_i, wi_i) |cos theta_i|, pdf) with normals +z. */
kernel void probe_bsdf_eval(global const Material* m, uint count, global const float4* wo, global const float4* wi,
                            global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float3 n = (float3)(0.0f, 0.0f, 1.0f);
    float pdf;
    CLP_PROBE_DECLARE_NO_LAYERS
#ifdef CLP_SURFACE_PARAMS
    Material mp = *m;
    float3 f = material_eval(&mp, n, n, wo[i].xyz, wi[i].xyz, &pdf CLP_PROBE_NO_LAYERS);
#else
    float3 f = material_eval(m, n, n, wo[i].xyz, wi[i].xyz, &pdf);
#endif
    out[i] = (float4)(f, pdf);
}

/* out[0] = material_is_delta(m). */
kernel void probe_bsdf_is_delta(global const Material* m, global int* out) {
#ifdef CLP_SURFACE_PARAMS
    Material mp = *m;
    out[0] = material_is_delta(&mp);
#else
    out[0] = material_is_delta(m);
#endif
}

/* Points sampled on triangle light l as seen from p: out[i] = (q, pdf) with the
 * solid-angle pdf without the pick, or pdf = -1 where the sample gave nothing.
 * pdf_out[i]: the pdf that MIS evaluates for the same direction and distance. */
kernel void probe_triangle_light(global const Light* l, float px, float py, float pz, uint count, uint seed,
                                 global float4* out, global float* pdf_out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    Rng r = rng_seed(i, 2, seed);
    float u1 = rng_next(&r), u2 = rng_next(&r);
    float3 p = (float3)(px, py, pz);
    LightSample s;
    if (!sample_triangle_light(l, p, u1, u2, &s)) {
        out[i] = (float4)(0.0f, 0.0f, 0.0f, -1.0f);
        pdf_out[i] = -1.0f;
        return;
    }
    float3 q = s.to; /* the shadow-ray end: q moved off the light by its error bound */
    out[i] = (float4)(q, s.pdf);
    pdf_out[i] = triangle_sample_pdf(l, p, s.wi, length(q - p));
}

#ifdef CLP_HAS_TEXTURES
/* out[i] = texture `index` sampled at uv[i] (sRGB decoded when srgb). */
kernel void probe_texture(global const TextureDesc* desc, global const uint* texels, int index, int srgb, uint count,
                          global const float2* uv, global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    SurfaceData sd;
    sd.desc = desc;
    sd.texels = texels;
    sd.attrs = 0;
    sd.material_ext = 0;
    sd.attr_stride = 0;
    sd.flags = 0;
    out[i] = texture_sample(&sd, index, uv[i], srgb);
}
#endif

/* The light BVH's pick at pn[i] = (p, u), normal nn[i].xyz: out[i] = (light
 * as bits, the sampler's pmf, the trail walk's pmf of that light, -). */
kernel void probe_light_bvh(global const LightBvhNode* nodes, global const uint2* trail, global const uint* infinite,
                            float4 origin, float4 scale, uint node_count, uint infinite_count, uint count,
                            global const float4* pn, global const float4* nn, global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    LightBvhData t;
    t.nodes = nodes;
    t.trail = trail;
    t.infinite = infinite;
    t.origin = origin.xyz;
    t.scale = scale.xyz;
    t.node_count = node_count;
    t.infinite_count = infinite_count;
    float3 p = pn[i].xyz, n = nn[i].xyz;
    float pmf = 0.0f;
    uint li = light_bvh_sample(&t, p, n, pn[i].w, &pmf);
    int inf = 0;
    for (uint k = 0; k < infinite_count; ++k) inf |= infinite[k] == li;
    float walk = li == CLP_NO_LIGHT ? 0.0f : light_bvh_pmf(&t, p, n, li, inf);
    out[i] = (float4)(as_float(li), pmf, walk, 0.0f);
}

#endif
