/* A hit's material with its textures and vertex colour applied
 * (CLP_SURFACE_PARAMS, textures.cl): base colour x texture (sRGB) x vertex
 * colour; roughness x G and metallic x B of the metallic-roughness texture
 * (glTF's channel layout); emission x emission texture (sRGB); and the
 * shading normal bent by a tangent-space normal map. */

#ifndef CLP_SURFACE_PARAMS_CL
#define CLP_SURFACE_PARAMS_CL

#include "textures.cl"
#include "materials.cl"
#include "traverse.cl"

#ifdef CLP_SURFACE_PARAMS

/* With instances, the hit's instance record (traverse_instances.cl): the
 * attributes are the object's, and its tangents move to world space with it. */
#ifdef CLP_HAS_INSTANCES
#define CLP_INST_PARAM , global const float4* im
#define CLP_INST_ARG(x) , x
#else
#define CLP_INST_PARAM
#define CLP_INST_ARG(x)
#endif

#ifdef CLP_HAS_TEXTURES
/* The tangent frame's tangent and bitangent sign at a hit: from the mesh's
 * tangents when it has them, else derived from how the texture coordinates
 * run across the triangle (constant per triangle). glTF's convention:
 * bitangent = cross(normal, tangent) * sign points along -v (v runs down the image). */
static inline float4 surface_tangent(const SurfaceData* sd, global const TriVerts* tv, float b1, float b2 CLP_INST_PARAM) {
    uint prim = tv->prim;
#ifdef CLP_HAS_INSTANCES
    const float handed = instance_handedness(im);
#else
    const float handed = 1.0f;
#endif
    if (sd->flags & CLP_SCENE_TANGENTS) {
        global const float* a = surface_attrs(sd, prim) + surface_tangent_offset(sd);
        float4 t0 = vload4(0, a), t1 = vload4(1, a), t2 = vload4(2, a);
#ifdef CLP_HAS_INSTANCES
        /* Each corner's tangent moved and made unit before the interpolation,
         * as a flattened copy's are (normalising does not commute with it). */
        t0.xyz = normalize3(instance_dir(im, t0.xyz));
        t1.xyz = normalize3(instance_dir(im, t1.xyz));
        t2.xyz = normalize3(instance_dir(im, t2.xyz));
#endif
        float4 t = (1.0f - b1 - b2) * t0 + b1 * t1 + b2 * t2;
        if (dot(t.xyz, t.xyz) > 0.0f) return (float4)(t.xyz, (t0.w < 0.0f ? -1.0f : 1.0f) * handed);
    }
    if (!(sd->flags & CLP_SCENE_UVS)) return (float4)(0.0f);
    global const float* a = surface_attrs(sd, prim);
    float2 uv0 = vload2(0, a), d1 = vload2(1, a) - uv0, d2 = vload2(2, a) - uv0;
    float3 v0 = load3g(tv->v0), e1 = load3g(tv->v1) - v0, e2 = load3g(tv->v2) - v0;
    float r = d1.x * d2.y - d2.x * d1.y;
    if (!(fabs(r) > 0.0f)) return (float4)(0.0f);
    float3 dpdu = (e1 * d2.y - e2 * d1.y) / r, dpdv = (e2 * d1.x - e1 * d2.x) / r;
    float3 n = cross(e1, e2);
    float w = (dot(cross(n, dpdu), dpdv) > 0.0f ? -1.0f : 1.0f) * handed;
#ifdef CLP_HAS_INSTANCES
    dpdu = instance_dir(im, dpdu); /* object-space edges: dp/du moves with the instance */
#endif
    return (float4)(dpdu, w);
}

/* ns bent by the tangent-space normal map `tex`, its x and y scaled by `scale`. */
static inline float3 normal_mapped(const SurfaceData* sd, int tex, float scale, float4 t, float2 uv, float3 ns) {
    float3 tn = texture_sample(sd, tex, uv, 0).xyz * 2.0f - 1.0f;
    tn.x *= scale;
    tn.y *= scale;
    float3 T = t.xyz - ns * dot(ns, t.xyz);
    float len = length3(T);
    if (!(len > 0.0f) || !isfinite(len)) return ns;
    T /= len;
    float3 B = cross(ns, T) * t.w;
    float3 n = T * tn.x + B * tn.y + ns * tn.z;
    float nl = length3(n);
    return nl > 0.0f && isfinite(nl) ? n / nl : ns;
}
#endif

#ifdef CLP_HAS_TEXTURES
#define CLP_TANGENT_PARAM , float4 tangent
#define CLP_TANGENT_ARG , tangent
#else
#define CLP_TANGENT_PARAM
#define CLP_TANGENT_ARG
#endif

#ifdef CLP_GLTF_LAYERS
/* The glTF layers of material mi at a hit (ns: the interpolated normal, before
 * the base's normal map, which the coat does not share): factors times their
 * textures (weight R, roughness G, transmission R, all linear). */
static inline void surface_layers(const SurfaceData* sd, global const Material* gm, uint mi, global const TriVerts* tv,
                                  float b1, float b2, float3 ns, GltfLayers* out CLP_TANGENT_PARAM) {
    out->coat_n = ns;
    out->clearcoat = 0.0f;
    out->coat_roughness = 0.0f;
    out->transmission = 0.0f;
    if (!(sd->flags & CLP_SCENE_MATERIAL_EXT) || gm->kind != CLP_MAT_GLTF) return;
    global const MaterialExt* ext = &sd->material_ext[mi];
    float c = ext->clearcoat, cr = ext->clearcoat_roughness, t = ext->transmission;
#ifdef CLP_HAS_TEXTURES
    int ct = ext->texture[CLP_TEX_CLEARCOAT], crt = ext->texture[CLP_TEX_CLEARCOAT_ROUGHNESS];
    int cnt = ext->texture[CLP_TEX_CLEARCOAT_NORMAL], tt = ext->texture[CLP_TEX_TRANSMISSION];
    if (ct != CLP_NO_TEXTURE || crt != CLP_NO_TEXTURE || cnt != CLP_NO_TEXTURE || tt != CLP_NO_TEXTURE) {
        float2 uv = surface_uv(sd, tv->prim, b1, b2);
        if (ct != CLP_NO_TEXTURE) c *= texture_sample(sd, ct, uv, 0).x;
        if (crt != CLP_NO_TEXTURE) cr *= texture_sample(sd, crt, uv, 0).y;
        if (tt != CLP_NO_TEXTURE) t *= texture_sample(sd, tt, uv, 0).x;
        if (cnt != CLP_NO_TEXTURE && c > 0.0f) out->coat_n = normal_mapped(sd, cnt, ext->clearcoat_normal_scale, tangent, uv, ns);
    }
#endif
    out->clearcoat = clamp(c, 0.0f, 1.0f);
    out->coat_roughness = clamp(cr, 0.0f, 1.0f);
    out->transmission = clamp(t, 0.0f, 1.0f);
}
#endif

#ifdef CLP_GLTF_LAYERS
#define CLP_LAYERS_OUT , GltfLayers* layers
#else
#define CLP_LAYERS_OUT
#endif

/* gm is material `mi` of the table (its MaterialExt has the same index). */
static inline void surface_params(const SurfaceData* sd, global const Material* gm, uint mi, global const TriVerts* tv,
                                  float b1, float b2, float3* ns, Material* out CLP_LAYERS_OUT CLP_INST_PARAM) {
    *out = *gm;
#ifdef CLP_HAS_TEXTURES
    /* A kernel with every feature may render a scene whose materials map nothing: no records then. */
    global const MaterialExt* ext = &sd->material_ext[mi];
    const int ext_here = (sd->flags & CLP_SCENE_MATERIAL_EXT) != 0;
    /* One tangent frame for both normal maps (the base's and the coat's). */
    float4 tangent = (float4)(0.0f);
    if (ext_here && (ext->texture[CLP_TEX_NORMAL] != CLP_NO_TEXTURE || ext->texture[CLP_TEX_CLEARCOAT_NORMAL] != CLP_NO_TEXTURE))
        tangent = surface_tangent(sd, tv, b1, b2 CLP_INST_ARG(im));
#endif
#ifdef CLP_GLTF_LAYERS
    surface_layers(sd, gm, mi, tv, b1, b2, *ns, layers CLP_TANGENT_ARG);
#endif
    float3 base = CLP_M3(gm->albedo);
#ifdef CLP_HAS_VERTEX_COLORS
    base *= surface_color(sd, tv->prim, b1, b2).xyz;
#endif
#ifdef CLP_HAS_TEXTURES
    int any = ext_here &&
              (ext->texture[0] != CLP_NO_TEXTURE || ext->texture[1] != CLP_NO_TEXTURE ||
               ext->texture[2] != CLP_NO_TEXTURE || ext->texture[3] != CLP_NO_TEXTURE);
    if (any) {
        float2 uv = surface_uv(sd, tv->prim, b1, b2);
        int t = ext->texture[CLP_TEX_BASE];
        if (t != CLP_NO_TEXTURE) base *= texture_sample(sd, t, uv, 1).xyz;
        t = ext->texture[CLP_TEX_MR];
        if (t != CLP_NO_TEXTURE) {
            float4 mr = texture_sample(sd, t, uv, 0);
            out->roughness *= mr.y;
            out->metallic *= mr.z;
        }
        t = ext->texture[CLP_TEX_EMISSION];
        if (t != CLP_NO_TEXTURE) {
            float3 e = CLP_M3(gm->emission) * texture_sample(sd, t, uv, 1).xyz;
            out->emission[0] = e.x;
            out->emission[1] = e.y;
            out->emission[2] = e.z;
        }
        if (ext->texture[CLP_TEX_NORMAL] != CLP_NO_TEXTURE)
            *ns = normal_mapped(sd, ext->texture[CLP_TEX_NORMAL], ext->normal_scale, tangent, uv, *ns);
    }
#endif
    out->albedo[0] = base.x;
    out->albedo[1] = base.y;
    out->albedo[2] = base.z;
}

#endif

#endif
