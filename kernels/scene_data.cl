/* What every kernel that follows paths through the scene shares: the scene
 * as one struct (SceneData, made from the kernel's CLP_SCENE_PARAMS), the
 * surface at a hit, closest-hit and shadow tracing, Russian roulette and the
 * tiled order of pixels. The megakernel (integrator.cl) and the wavefront
 * kernels (wavefront.cl) both build on it. */
#ifndef CLP_SCENE_DATA_CL
#define CLP_SCENE_DATA_CL

#include "common.h"
#include "rng.cl"
#include "sampling.cl"
#include "camera.cl"
#include "traverse.cl"
#include "materials.cl"
#include "surface_params.cl"
#include "lights.cl"
#include "light_bvh.cl"

/* Both come from the host's settings, never from a default here. */
#if !defined(CLP_INTEGRATOR) || !defined(CLP_MAX_DEPTH)
#error "build with -DCLP_INTEGRATOR and -DCLP_MAX_DEPTH (host/render/kernel_features.cpp build_options)"
#endif

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
#ifdef CLP_LIGHT_BVH
    LightBvhData lbvh; /* next-event estimation picks lights by the light BVH (light_bvh.cl) */
#endif
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
#ifdef CLP_GLTF_LAYERS
    GltfLayers layers; /* mat's clear coat and transmission (surface_params.cl) */
#endif
} Surface;

#ifdef CLP_SURFACE_PARAMS
#define surface_material(s) (&(s)->mat)
#else
#define surface_material(s) ((s)->m)
#endif
/* The BSDF's arguments after the material's: the layers where compiled in. */
#ifdef CLP_GLTF_LAYERS
#define surface_layers_arg(s) CLP_LAYERS_ARG(&(s)->layers)
#else
#define surface_layers_arg(s)
#endif


/* The point h found, in world space, with its rounding-error bound *err and
 * the triangle's unit geometric normal *ng (of the winding; with instances,
 * moved to world space by instance_normal). */
static inline float3 surface_point(const SceneData* sc, const Hit* h, float3* ng, float3* err) {
    global const TriVerts* tv = &sc->tris[h->tri];
    float3 v0 = load3g(tv->v0), v1 = load3g(tv->v1), v2 = load3g(tv->v2);
#ifdef CLP_HAS_INSTANCES
    /* The triangle is in its instance's object space: the point and its
     * error bound go to world space with the vertices (instance_hit_point),
     * the normal with the inverse transpose. */
    global const float4* im = (global const float4*)&sc->nodes[h->inst];
    *ng = instance_normal(im, cross(v1 - v0, v2 - v0));
    return instance_hit_point(im, v0, v1, v2, h->b1, h->b2, err);
#else
    *ng = normalize3(cross(v1 - v0, v2 - v0));
    return hit_point(v0, v1, v2, h->b1, h->b2, err);
#endif
}

/* The surface a hit found, written to *out (not returned: see no_hit in
 * traverse_leaf.cl). Forced inline on a GPU: the wavefront's shading kernels
 * each recompute it, and kept out of line it is handed back through the
 * GPU's stack. */
CLP_GPU_INLINE void surface_at(Surface* out, const SceneData* sc, const Hit* h, float3 d) {
    Surface s;
    s.tv = &sc->tris[h->tri];
    s.p = surface_point(sc, h, &s.ng, &s.err);
    s.front = dot(s.ng, d) < 0.0f;
    uint mi = sc->tri_material[s.tv->prim];
    s.m = &sc->materials[mi];
    s.ns = s.ng;
#ifdef CLP_HAS_NORMALS
    if (sc->fp->scene_flags & CLP_SCENE_NORMALS) {
    global const float* n = sc->normals + 9 * (size_t)s.tv->prim;
#ifdef CLP_HAS_INSTANCES
    global const float4* im = (global const float4*)&sc->nodes[h->inst];
    /* Each corner's normal moved and made unit before the interpolation, as
     * a flattened copy's are (normalising does not commute with it). */
    float3 ns = (1.0f - h->b1 - h->b2) * instance_normal(im, vload3(0, n)) + h->b1 * instance_normal(im, vload3(1, n)) +
                h->b2 * instance_normal(im, vload3(2, n));
#else
    float3 ns = (1.0f - h->b1 - h->b2) * vload3(0, n) + h->b1 * vload3(1, n) + h->b2 * vload3(2, n);
#endif
    float len = length3(ns);
    if (len > 0.0f && isfinite(len)) s.ns = ns / len;
    }
#endif
#ifdef CLP_SURFACE_PARAMS
    surface_params(&sc->sd, s.m, mi, s.tv, h->b1, h->b2, &s.ns, &s.mat surface_layers_arg(&s)
                   CLP_INST_ARG((global const float4*)&sc->nodes[h->inst]));
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

/* The scene a kernel was handed (CLP_SCENE_PARAMS, then the frame's
 * parameters), as one struct: scene_data(&sc, CLP_SCENE_ARGS fp). Filled
 * through a pointer, as every struct here (traverse_leaf.cl: Oclgrind cannot
 * run the inlined struct returns). */
#define CLP_SCENE_ARG(type, name) name,
#define CLP_SCENE_ARGS CLP_SCENE_BUFFERS(CLP_SCENE_ARG)
static inline void scene_data(SceneData* out, CLP_SCENE_PARAMS constant const FrameParams* fp) {
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
#ifdef CLP_LIGHT_BVH
    sc.lbvh.nodes = light_bvh;
    sc.lbvh.trail = (global const uint2*)light_trails;
    sc.lbvh.infinite = light_infinite;
    sc.lbvh.origin = load3c(fp->lbvh_origin);
    sc.lbvh.scale = load3c(fp->lbvh_scale);
    sc.lbvh.node_count = fp->lbvh_node_count;
    sc.lbvh.infinite_count = fp->lbvh_infinite_count;
#endif
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
    /* The layout the program was built for (the host checks that it is the
     * scene's): tested at run time inside the walk, the layout's flags cost
     * the closest-hit walk 3 registers at sm_90, past its budget of 64. */
    sc.alpha.sd.flags = CLP_ALPHA_ATTRIBUTES;
    sc.alpha.tri_material = tri_material;
#endif
    *out = sc;
}

#endif
