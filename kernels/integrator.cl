/* The path tracer: one work-item per pixel, `samples` paths each, each sample
 * added to the pixel's running sum in sample order (so the image does not
 * depend on how the host splits the work into launches). */

#ifndef CLP_TILE
#define CLP_TILE 8 /* pixels are walked in 8x8 tiles: neighbouring work-items trace neighbouring rays */
#endif

inline int tile_to_pixel(uint i, uint width, uint height, uint* px, uint* py) {
    uint tiles_x = (width + CLP_TILE - 1) / CLP_TILE;
    uint tile = i / (CLP_TILE * CLP_TILE), in = i % (CLP_TILE * CLP_TILE);
    *px = (tile % tiles_x) * CLP_TILE + in % CLP_TILE;
    *py = (tile / tiles_x) * CLP_TILE + in / CLP_TILE;
    return *px < width && *py < height;
}

inline float max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

/* Russian roulette: returns 0 to end the path, else divides the throughput by
 * the survival probability, which keeps the estimate unbiased. */
inline int russian_roulette(constant const FrameParams* fp, uint depth, float3* beta, Rng* rng) {
    float q = 1.0f;
    if (fp->rr_rule == CLP_RR_THROUGHPUT && depth >= fp->rr_min_depth)
        q = fmin(max3(*beta), 1.0f);
    else if (fp->rr_rule == CLP_RR_DEPTH)
        q = 1.0f - 1.0f / (float)(fp->max_depth - depth); /* the thesis renderer's rule */
    if (q >= 1.0f) return 1;
    if (q <= 0.0f || rng_next(rng) >= q) return 0;
    *beta /= q;
    return 1;
}

/* One path from the camera ray; returns its radiance estimate. *rays counts
 * every ray traced. */
inline float3 trace_path(global const BvhNode* nodes, global const TriVerts* tris, global const uint* tri_material,
                         global const Material* materials, constant const FrameParams* fp, Ray ray, Rng* rng,
                         uint* rays) {
    float3 L = (float3)(0.0f), beta = (float3)(1.0f);
    for (uint depth = 0;; ++depth) {
        RayPre rp = ray_prepare(ray.o, ray.d);
        Hit h = traverse_bvh(nodes, tris, &rp, INFINITY, 0, 0);
        ++*rays;
        if (h.tri < 0) break;
        global const TriVerts* tv = &tris[h.tri];
        float3 v0 = load3g(tv->v0), v1 = load3g(tv->v1), v2 = load3g(tv->v2);
        float3 ng = normalize(cross(v1 - v0, v2 - v0));
        int front = dot(ng, ray.d) < 0.0f;
        global const Material* m = &materials[tri_material[tv->prim]];
        L += beta * material_emission(m, front);
        if (depth >= fp->max_depth || !material_scatters(m)) break;
        if (!russian_roulette(fp, depth, &beta, rng)) break;
        float3 n = front ? ng : -ng; /* the side the ray came from */
        float u1 = rng_next(rng), u2 = rng_next(rng);
        float3 wi;
        beta *= material_sample(m, n, u1, u2, &wi);
        float3 err;
        float3 p = hit_point(v0, v1, v2, h.b1, h.b2, &err);
        ray.o = offset_ray_origin(p, err, ng, wi);
        ray.d = wi;
    }
    return L;
}

kernel void render_paths(global const BvhNode* nodes, global const TriVerts* tris, global const uint* tri_material,
                         global const Material* materials, constant const FrameParams* fp,
                         global AccumPixel* accum, global Counters* counters) {
    local uint group_rays, group_nonfinite;
    if (get_local_id(0) == 0) group_rays = group_nonfinite = 0;
    barrier(CLK_LOCAL_MEM_FENCE);

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
            float3 L = trace_path(nodes, tris, tri_material, materials, fp, ray, &rng, &rays);
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
