/* Textures and per-vertex surface attributes (texture coordinates, tangents,
 * vertex colours), and the alpha test that traversal calls for cut-outs.
 *
 * Textures live in one global buffer of uints with a descriptor each
 * (TextureDesc), not in OpenCL images: images are optional on some devices
 * and limited in count and size. 8-bit texels are RGBA8 in one uint, float
 * texels four uints. Filtering is bilinear (or nearest, as the sampler says),
 * addressing repeat, clamp-to-edge or mirrored repeat per axis; colour
 * textures are decoded from sRGB per texel, before filtering.
 *
 * Compiled in only for scenes that need them: CLP_HAS_TEXTURES (a material
 * maps a texture), CLP_HAS_VERTEX_COLORS, CLP_HAS_ALPHA (a MASK or BLEND
 * material), CLP_HAS_MAT_GLTF. With textures or vertex colours a hit's
 * material is a private copy with them applied (CLP_SURFACE_PARAMS), and the
 * material functions take private pointers; otherwise they read the global
 * material table directly, as before. Texture slots and coverage are in the
 * MaterialExt buffer (shared_structs.h), read only here and by
 * surface_params.cl, and only under CLP_HAS_TEXTURES or CLP_HAS_ALPHA. */
#ifndef CLP_TEXTURES_CL
#define CLP_TEXTURES_CL

#include "common.h"
#include "rng.cl"
#include "intersect.cl"

/* The glTF layers (KHR_materials_clearcoat, KHR_materials_transmission) are
 * per-hit parameters beside the material (GltfLayers, materials.cl), read
 * from the MaterialExt records by surface_params. */
#if defined(CLP_HAS_CLEARCOAT) || defined(CLP_HAS_TRANSMISSION)
#define CLP_GLTF_LAYERS 1
#endif

#if defined(CLP_HAS_TEXTURES) || defined(CLP_HAS_VERTEX_COLORS) || defined(CLP_GLTF_LAYERS)
#define CLP_SURFACE_PARAMS 1
#define CLP_MAT_SPACE
#else
#define CLP_MAT_SPACE global
#endif

typedef struct {
    global const TextureDesc* desc;
    global const uint* texels;
    global const float* attrs; /* fp->attr_stride floats per triangle, in scene order */
    global const MaterialExt* material_ext; /* per material when flags has CLP_SCENE_MATERIAL_EXT */
    uint attr_stride;
    uint flags; /* CLP_SCENE_* */
} SurfaceData;

/* ---- texture lookup ----------------------------------------------------- */

static inline float srgb_to_linear(float c) {
    return c <= 0.04045f ? c * (1.0f / 12.92f) : pow((c + 0.055f) * (1.0f / 1.055f), 2.4f);
}

static inline float4 texel_fetch(const SurfaceData* sd, global const TextureDesc* d, int x, int y, int srgb) {
    uint i = (uint)y * d->width + (uint)x;
    float4 c;
    if (d->flags & CLP_TEXF_FLOAT) {
        global const uint* p = sd->texels + d->offset + 4u * i;
        c = (float4)(as_float(p[0]), as_float(p[1]), as_float(p[2]), as_float(p[3]));
    } else {
        uint p = sd->texels[d->offset + i];
        c = (float4)((float)(p & 255u), (float)((p >> 8) & 255u), (float)((p >> 16) & 255u), (float)(p >> 24)) *
            (1.0f / 255.0f);
        if (srgb) c = (float4)(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z), c.w);
    }
    return c;
}

/* A texel index i (any integer) into [0, n) by the wrap mode. */
static inline int wrap_index(int i, int n, uint mode) {
    if (mode == CLP_WRAP_CLAMP) return clamp(i, 0, n - 1);
    if (mode == CLP_WRAP_MIRROR) {
        int p = i % (2 * n);
        if (p < 0) p += 2 * n;
        return p < n ? p : 2 * n - 1 - p;
    }
    int p = i % n;
    return p < 0 ? p + n : p;
}

/* A coordinate folded into one period of its wrap mode, so that the texel
 * index below stays a small integer whatever the coordinate's size. */
static inline float wrap_coord(float u, uint mode) {
    if (!isfinite(u)) return 0.0f;
    if (mode == CLP_WRAP_CLAMP) return clamp(u, 0.0f, 1.0f);
    if (mode == CLP_WRAP_MIRROR) return u - 2.0f * floor(0.5f * u); /* [0, 2): the mirror is in wrap_index */
    return u - floor(u);
}

/* Texture `index` at (u, v), v down (row 0 at v = 0), as glTF defines it. */
static inline float4 texture_sample(const SurfaceData* sd, int index, float2 uv, int srgb) {
    global const TextureDesc* d = &sd->desc[index];
    uint ws = (d->flags >> CLP_TEXF_WRAP_S_SHIFT) & 3u, wt = (d->flags >> CLP_TEXF_WRAP_T_SHIFT) & 3u;
    int w = (int)d->width, h = (int)d->height;
    float x = wrap_coord(uv.x, ws) * (float)w, y = wrap_coord(uv.y, wt) * (float)h;
    if (d->flags & CLP_TEXF_NEAREST)
        return texel_fetch(sd, d, wrap_index((int)floor(x), w, ws), wrap_index((int)floor(y), h, wt), srgb);
    /* Bilinear between the four texel centres around (x, y). */
    x -= 0.5f;
    y -= 0.5f;
    float fx0 = floor(x), fy0 = floor(y);
    float tx = x - fx0, ty = y - fy0;
    int x0 = (int)fx0, y0 = (int)fy0;
    int xa = wrap_index(x0, w, ws), xb = wrap_index(x0 + 1, w, ws);
    int ya = wrap_index(y0, h, wt), yb = wrap_index(y0 + 1, h, wt);
    float4 c00 = texel_fetch(sd, d, xa, ya, srgb), c10 = texel_fetch(sd, d, xb, ya, srgb);
    float4 c01 = texel_fetch(sd, d, xa, yb, srgb), c11 = texel_fetch(sd, d, xb, yb, srgb);
    return mix(mix(c00, c10, tx), mix(c01, c11, tx), ty);
}

/* ---- per-vertex attributes ---------------------------------------------- */

static inline global const float* surface_attrs(const SurfaceData* sd, uint prim) {
    return sd->attrs + (size_t)prim * sd->attr_stride;
}

static inline float2 surface_uv(const SurfaceData* sd, uint prim, float b1, float b2) {
    if (!(sd->flags & CLP_SCENE_UVS)) return (float2)(0.0f);
    global const float* a = surface_attrs(sd, prim);
    return (1.0f - b1 - b2) * vload2(0, a) + b1 * vload2(1, a) + b2 * vload2(2, a);
}

static inline uint surface_tangent_offset(const SurfaceData* sd) { return (sd->flags & CLP_SCENE_UVS) ? 6u : 0u; }
static inline uint surface_color_offset(const SurfaceData* sd) {
    return surface_tangent_offset(sd) + ((sd->flags & CLP_SCENE_TANGENTS) ? 12u : 0u);
}

static inline float4 surface_color(const SurfaceData* sd, uint prim, float b1, float b2) {
    if (!(sd->flags & CLP_SCENE_COLORS)) return (float4)(1.0f);
    global const float* a = surface_attrs(sd, prim) + surface_color_offset(sd);
    return (1.0f - b1 - b2) * vload4(0, a) + b1 * vload4(1, a) + b2 * vload4(2, a);
}

/* Coverage of a hit: base colour alpha x texture alpha x vertex colour alpha. */
static inline float surface_alpha(const SurfaceData* sd, global const MaterialExt* m, uint prim, float b1, float b2) {
    float a = m->alpha;
#ifdef CLP_HAS_TEXTURES
    if (m->texture[CLP_TEX_BASE] != CLP_NO_TEXTURE)
        a *= texture_sample(sd, m->texture[CLP_TEX_BASE], surface_uv(sd, prim, b1, b2), 0).w;
#endif
#ifdef CLP_HAS_VERTEX_COLORS
    a *= surface_color(sd, prim, b1, b2).w;
#endif
    return a;
}

/* ---- alpha cut-outs, for traversal --------------------------------------- */

#ifdef CLP_HAS_ALPHA
typedef struct {
    SurfaceData sd; /* its material_ext holds every material's coverage (a scene with alpha has them) */
    global const uint* tri_material;
} AlphaScene;

/* Whether a ray's hit on triangle `prim` counts. MASK: alpha >= cutoff.
 * BLEND: kept with probability alpha (stochastic coverage: the expected
 * transmittance is 1 - alpha, as alpha blending would give), decided by a
 * hash of the ray and the triangle, so one ray always sees the same thing. */
static inline int alpha_keeps_hit(const AlphaScene* as, uint prim, float b1, float b2, const RayPre* r) {
    global const MaterialExt* m = &as->sd.material_ext[as->tri_material[prim]];
    if (m->alpha_mode == CLP_ALPHA_OPAQUE) return 1;
    float a = surface_alpha(&as->sd, m, prim, b1, b2);
    if (m->alpha_mode == CLP_ALPHA_MASK) return a >= m->alpha_cutoff;
    uint h = hash_u32(prim ^ hash_u32(as_uint(r->org.x) ^ hash_u32(as_uint(r->org.y) ^ hash_u32(as_uint(r->org.z) ^
                      hash_u32(as_uint(r->dir.x) ^ hash_u32(as_uint(r->dir.y) + as_uint(r->dir.z)))))));
    return (float)(h >> 8) * 0x1.0p-24f < a;
}
#define CLP_ALPHA_PARAM , const AlphaScene* alpha
#define CLP_ALPHA_ARG , alpha
#else
#define CLP_ALPHA_PARAM
#define CLP_ALPHA_ARG
#endif

#endif
