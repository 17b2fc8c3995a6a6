/*
 * clpath: the structs that host and kernels both read. This one header is
 * included by the C++ host and prepended to every OpenCL program, so a layout
 * is defined exactly once.
 *
 * Layout rules (why no float3 anywhere): OpenCL's float3 is 16 bytes and
 * 16-byte aligned, the host's float[3] is 12 bytes, so a float3 member would
 * silently shift every later field. Every struct here is made of 4-byte
 * scalars and fixed arrays only, sized to a multiple of 16 bytes, and its size
 * is asserted on both sides (bottom of this file).
 */
#ifndef CLPATH_SHARED_STRUCTS_H
#define CLPATH_SHARED_STRUCTS_H

#ifdef __OPENCL_C_VERSION__
#define CLP_STATIC_ASSERT(cond, name) typedef char clp_static_assert_##name[(cond) ? 1 : -1]
#else
#include <cstdint>
typedef std::uint32_t uint;
#define CLP_STATIC_ASSERT(cond, name) static_assert(cond, #name)
#endif

/* Deepest BVH the builder may produce, and so the traversal stack size. The
 * builder forces balanced splits before it gets there (host/bvh/). 40 levels
 * hold a balanced tree of 2^39 leaves, far past CLP_BVH4_MAX_NODES, and SAH
 * trees of real scenes stay well within it (bunny 20, room:1003542 25, 10
 * million triangles 28); each level costs the 4-wide traversal 6 bytes of
 * stack per ray (CLP_BVH4_STACK), which on a GPU is off-chip memory: at 40
 * its stack is 244 bytes, under the 256 a GPU traversal kernel is held to. */
#define CLP_BVH_MAX_DEPTH 40

/* Material kinds: how a surface scatters. This table is the one list of them:
 * the CLP_MAT_* values, the kernels' CLP_HAS_MAT_<KIND> switches, the scene
 * file's material types and the exporters are generated from it or checked
 * against it (tests/scene/material_kinds_test.cpp). Any kind may also emit
 * (emission > 0); a pure emitter is a diffuse material of albedo 0. A program
 * is compiled only with the kinds a scene uses.
 * X(KIND, name, whether a scene file names it as "type": "name"):
 *   DIFFUSE     Lambert, albedo
 *   MIRROR      perfect specular reflection tinted by albedo
 *   CONDUCTOR   GGX microfacet reflection: roughness, Schlick Fresnel with F0 = albedo
 *   DIELECTRIC  glass: Fresnel reflection and refraction, ior; rough when roughness > 0
 *   GLTF        glTF metallic-roughness: Lambert under a GGX dielectric coat, mixed with a GGX
 *               conductor by metallic (glTF 2.0 specification, appendix B); made by glTF files
 *               and textured MTL materials */
#define CLP_MATERIAL_KINDS(X)                                                               \
    X(DIFFUSE, diffuse, 1) X(MIRROR, mirror, 1) X(CONDUCTOR, conductor, 1) X(DIELECTRIC, dielectric, 1) \
    X(GLTF, gltf, 0)
#define CLP_MAT_ENUMERATOR(KIND, name, in_scene_files) CLP_MAT_##KIND,
enum { CLP_MATERIAL_KINDS(CLP_MAT_ENUMERATOR) CLP_MAT_KIND_COUNT };
#undef CLP_MAT_ENUMERATOR

/* MaterialExt.alpha_mode: how a surface's coverage (base colour alpha) is used. */
#define CLP_ALPHA_OPAQUE 0u /* alpha ignored */
#define CLP_ALPHA_MASK 1u   /* a hit with alpha < alpha_cutoff is not a hit (cut-out) */
#define CLP_ALPHA_BLEND 2u  /* a hit is kept with probability alpha (stochastic coverage) */

/* Texture addressing and texel formats (TextureDesc.flags). */
#define CLP_WRAP_REPEAT 0u
#define CLP_WRAP_CLAMP 1u
#define CLP_WRAP_MIRROR 2u
#define CLP_TEXF_WRAP_S_SHIFT 0u /* 2 bits each */
#define CLP_TEXF_WRAP_T_SHIFT 2u
#define CLP_TEXF_FLOAT 16u   /* texels are 4 floats (else 4 bytes, RGBA8, in one uint) */
#define CLP_TEXF_NEAREST 32u /* nearest texel instead of bilinear */
#define CLP_NO_TEXTURE (-1)

/* MaterialExt.texture slots. */
#define CLP_TEX_BASE 0u     /* base colour (sRGB) and alpha */
#define CLP_TEX_MR 1u       /* metallic (B) and roughness (G), linear */
#define CLP_TEX_NORMAL 2u   /* tangent-space normal, linear */
#define CLP_TEX_EMISSION 3u /* emission (sRGB) */
#define CLP_TEX_CORE_SLOTS 4u /* the core material's maps; the layers' follow */
#define CLP_TEX_CLEARCOAT 4u           /* KHR_materials_clearcoat: coat weight (R), linear */
#define CLP_TEX_CLEARCOAT_ROUGHNESS 5u /* coat roughness (G), linear */
#define CLP_TEX_CLEARCOAT_NORMAL 6u    /* the coat's tangent-space normal, linear */
#define CLP_TEX_TRANSMISSION 7u        /* KHR_materials_transmission: transmission (R), linear */
#define CLP_TEX_SLOTS 8u

/* Integrators (RenderSettings.integrator); each is compiled in alone. */
#define CLP_INTEGRATOR_PATH 0u      /* next-event estimation + MIS */
#define CLP_INTEGRATOR_PATH_BSDF 1u /* BSDF sampling only, as the thesis renderer */
#define CLP_INTEGRATOR_AO 2u        /* ambient occlusion, cosine-weighted, max distance */
#define CLP_INTEGRATOR_NORMALS 3u   /* shading normal, mapped to [0,1] */
#define CLP_INTEGRATOR_DEPTH 4u     /* distance along the camera ray */
#define CLP_INTEGRATOR_ALBEDO 5u    /* first-hit albedo */
#define CLP_INTEGRATOR_HEATMAP 6u   /* BVH nodes visited by the camera ray, false colour */
#define CLP_INTEGRATOR_COUNT 7u

/* Light kinds in the light table (one table, one alias table over it). */
#define CLP_LIGHT_TRIANGLE 0u    /* an emissive triangle: a, b, c its vertices, L its radiance */
#define CLP_LIGHT_POINT 1u       /* a: position, L: intensity (W/sr) */
#define CLP_LIGHT_SPOT 2u        /* a: position, b: axis, L: intensity, smooth falloff cos_outer..cos_inner */
#define CLP_LIGHT_DIRECTIONAL 3u /* b: direction the light travels, L: irradiance (W/m^2) */
#define CLP_LIGHT_ENVIRONMENT 4u /* FrameParams.env_*: a constant colour or an equirectangular image */
#define CLP_LIGHTF_TWO_SIDED 1u  /* a triangle light that emits from both faces */
#define CLP_NO_LIGHT 0xffffffffu

/* The path kernel walks pixels in CLP_TILE x CLP_TILE tiles, so that
 * neighbouring work-items trace neighbouring rays; the host launches whole
 * tiles (the pixel count rounded up to them). */
#define CLP_TILE 8u

/* Ray batches (clpath bench rays): pixels in CLP_BATCH_TILE x CLP_BATCH_TILE
 * tiles (width and height must be multiples of it), each with a
 * CLP_BATCH_GRID x CLP_BATCH_GRID grid of samples at its cells' centres. */
#define CLP_BATCH_TILE 4u
#define CLP_BATCH_GRID 4u
#define CLP_BATCH_SAMPLES (CLP_BATCH_GRID * CLP_BATCH_GRID)

/* The environment image's sampling distribution (PBR 4th ed., A.5.6) is one
 * float array: the marginal CDF over the h rows (h + 1 values), then each
 * row's conditional CDF over its w columns (w + 1 values each). An array
 * whose first value is CLP_ENV_NOT_SAMPLED (a negative number, which no CDF
 * starts with) means: sample the sphere uniformly instead. */
#define CLP_ENV_NOT_SAMPLED (-1.0f)
#define CLP_ENV_IS_SAMPLED(first_value) ((first_value) >= 0.0f)
#define CLP_ENV_ROW_CDF(w, h, y) ((h) + 1u + (y) * ((w) + 1u)) /* index of row y's conditional CDF */
#define CLP_ENV_CDF_SIZE(w, h) CLP_ENV_ROW_CDF(w, h, h)

/* Where a triangle light is sampled by solid angle (Arvo 1995) rather than
 * by area (kernels/lights.cl, triangle_sampled_solid_angle, says why): when
 * its area is at least MIN_SPREAD times the squared distance from the shading
 * point to its nearest vertex, its solid angle lies in [MIN_AREA, MAX_AREA]
 * (pbrt-v4's Triangle::Sample thresholds) and the shading point is at least
 * MIN_ELEVATION times its distance to the nearest vertex off the triangle's plane. */
#define CLP_MIN_SPHERICAL_SPREAD 0.1f
#define CLP_MIN_SPHERICAL_AREA 3e-4f
#define CLP_MAX_SPHERICAL_AREA 6.22f
#define CLP_MIN_SPHERICAL_ELEVATION 0.1f

/* FrameParams.scene_flags. */
#define CLP_SCENE_NORMALS 1u  /* the normals buffer holds per-vertex shading normals */
#define CLP_SCENE_UVS 2u      /* the attribute buffer holds texture coordinates (6 floats per triangle) */
#define CLP_SCENE_TANGENTS 4u /* ... then tangents (xyz and sign, 12 floats per triangle) */
#define CLP_SCENE_COLORS 8u   /* ... then vertex colours (RGBA, 12 floats per triangle) */
#define CLP_SCENE_MATERIAL_EXT 16u /* the MaterialExt buffer holds one record per material (else one zero record) */
/* The flags of the attribute buffer's layout. */
#define CLP_SCENE_ATTRIBUTES (CLP_SCENE_UVS | CLP_SCENE_TANGENTS | CLP_SCENE_COLORS)

/* Material flags. */
#define CLP_MATF_TWO_SIDED_EMISSION 1u /* emits from the back face too */

/* Russian roulette rules. */
#define CLP_RR_NONE 0u       /* trace every path to max_depth */
#define CLP_RR_THROUGHPUT 1u /* survive with p = max(throughput), after rr_min_depth bounces */
#define CLP_RR_DEPTH 2u      /* the thesis renderer's rule: p = 1 - 1/(max_depth - depth) */

/*
 * Node layouts are named by their size in bytes, the figure a traversal's
 * memory traffic follows; each is walked by its own kernel file
 * (kernels/traverse_*.cl).
 *
 * The binary BVH node, in the Aila & Laine (2009) "both children in one node"
 * layout: the builder's output (host/bvh/), widened into Bvh4Node128 for
 * traversal, and the record of the flat list of object boxes
 * (traverse_flat.cl); one fetch of 64 bytes holds both child boxes.
 * child[i] >= 0: index of an interior node.
 * child[i] <  0: a leaf holding count[i] triangles from ~child[i] on
 *                (count 0: an empty slot, used only when the root is a leaf).
 */
typedef struct {
    float lo0[3];
    int child0;
    float hi0[3];
    uint count0;
    float lo1[3];
    int child1;
    float hi1[3];
    uint count1;
} BvhNode64;

/*
 * The BVH as the kernels traverse it: four children per node, made from the
 * binary tree above by pulling grandchildren up (host/bvh/wide.hpp); 4-wide
 * nodes were the fastest layout for OpenCL on CPUs and GPUs in tinybvh's
 * measurements. The boxes are stored by coordinate (lo_x of the four
 * children in one row, ...), so one float4 slab test handles all four.
 * child[i] >= 0: index of an interior Bvh4Node128.
 * child[i] <  0: a leaf of count[i] (>= 1) triangles from ~child[i] on.
 * child[i] == 0 with count[i] == 0: an empty slot (no node has the root as a child).
 */
typedef struct {
    float lo_x[4];
    float hi_x[4];
    float lo_y[4];
    float hi_y[4];
    float lo_z[4];
    float hi_z[4];
    int child[4];
    uint count[4];
} Bvh4Node128;

/* The widening (host/bvh/wide.cpp) keeps the 4-wide tree at most half as
 * deep as the binary bound (where its first choice would not, it makes every
 * wide level span two binary levels), and a traversal keeps at most
 * three siblings per level on its stack, plus the one it is about to pop. */
#define CLP_BVH4_MAX_DEPTH (CLP_BVH_MAX_DEPTH / 2)
#define CLP_BVH4_STACK (3 * CLP_BVH4_MAX_DEPTH + 1)
/* Shadow rays push a leaf as ~(node * 4 + slot), a 32-bit int
 * (traverse_bvh4.cl, occlude_tree): so no more 4-wide nodes than this (host/bvh/wide.cpp). */
#define CLP_BVH4_MAX_NODES (1 << 29)

/* The BVH as CPUs walk it: eight children per node, the same rows widened
 * to eight lanes, so one float8 slab test (one AVX instruction per step)
 * handles all eight boxes; a tree about two thirds as deep as the 4-wide
 * one, for twice the bytes a node. On PoCL it traced 1.05-1.21x the rays
 * per second of Bvh4Node128 (cornell, bunny, room:1003542, scaling:1000;
 * about as many at 10^7 triangles, where cache misses set the pace;
 * benchmarks/results/pocl-epyc-2core/). GPUs keep Bvh4Node128: their
 * kernels are held to register and stack budgets measured on the 4-wide
 * walk (benchmarks/results/gpu-compile/), and instanced scenes too (their
 * two-level walk is 4-wide). Same conventions as Bvh4Node128: child[i] > 0
 * an interior node, < 0 a leaf of count[i] triangles from ~child[i],
 * child and count 0 an empty slot. */
typedef struct {
    float lo_x[8];
    float hi_x[8];
    float lo_y[8];
    float hi_y[8];
    float lo_z[8];
    float hi_z[8];
    int child[8];
    uint count[8];
} Bvh8Node256;

/* The widening falls back to spanning two binary levels per wide level as
 * for four children (host/bvh/wide.cpp), so the same depth bound holds; a
 * traversal keeps at most seven siblings per level, plus the one it is
 * about to pop. */
#define CLP_BVH8_MAX_DEPTH CLP_BVH4_MAX_DEPTH
#define CLP_BVH8_STACK (7 * CLP_BVH8_MAX_DEPTH + 1)
/* Shadow rays push a leaf as ~(node * 8 + slot) (traverse_bvh8.cl). */
#define CLP_BVH8_MAX_NODES (1 << 28)

/* Instancing (a two-level BVH, host/bvh/instances.hpp), compiled in only
 * for a scene that places a mesh by instances (-DCLP_HAS_INSTANCES): the node
 * buffer then holds the top-level 4-wide BVH over the instances' world boxes
 * from node 0, one Instance record per instance (128 bytes, a node's size,
 * so the records share the node buffer and no kernel gains an argument), and
 * every bottom-level BVH (one per mesh, its child indices and leaf ranges
 * already offset into the shared node and triangle buffers). A top-level
 * leaf holds exactly one instance: child = ~(the node index of its record).
 * Geometry placed once stays in one bottom-level BVH under an identity
 * instance, so every walk is top level, then bottom level.
 * The matrices are affine 3x4, rows of (m00 m01 m02 t0): p' = M p + t. */
typedef struct {
    float object_to_world[12];
    float world_to_object[12];
    uint blas_root;   /* node index of the mesh's bottom-level root */
    uint first_tri;   /* the mesh's first TriVerts (its leaves are already offset by it) */
    uint first_prim;  /* the mesh's first triangle in the per-triangle buffers (materials, normals) */
    float det_sign;   /* sign of det(M): -1 for a mirroring instance, whose winding (and so ng) flips */
    uint mesh;
    uint pad0, pad1, pad2;
} Instance;
/* The instanced walk keeps one stack for both levels: the top level's
 * pending siblings stay on it below the instance's walk, so it needs three
 * entries per 4-wide level of the top level plus the deepest bottom level it
 * enters, plus the one about to pop. That joint depth, not each level's, is
 * bounded: the host refuses a scene whose top level's 4-wide depth and its
 * deepest placed mesh's together pass CLP_INSTANCE_MAX_DEPTH4
 * (host/bvh/instances.cpp, build_two_level). At 18 the stack is 55 entries,
 * 220 bytes, and with the 8 slots below them (traverse_instances.cl) the
 * walk's 252 bytes stay under the 256 a GPU traversal kernel is held to;
 * 10,000 bunnies take 8 + 10. */
#define CLP_INSTANCE_MAX_DEPTH4 18
#define CLP_INSTANCE_STACK (3 * CLP_INSTANCE_MAX_DEPTH4 + 1)

/* Triangle as traversal reads it, in BVH leaf order. prim is the index of the
 * triangle in the scene's original order (for material and shading data);
 * light lets a path that hits an emitter find its light-sampling pdf (MIS). */
typedef struct {
    float v0[3];
    uint prim;
    float v1[3];
    uint light; /* index in the light table when the triangle emits, else CLP_NO_LIGHT */
    float v2[3];
    uint pad2;
} TriVerts;

/* A material: one record for every kind, read only by the kinds that use it.
 * It holds what every scene's kernels read, and keeps the 48 bytes it had
 * before textures and glTF materials: a scene without them fetches and copies
 * no more per hit than it did then. metallic sits in the spare word, read only
 * by the glTF kind's BSDF with the other lobe parameters. */
typedef struct {
    float albedo[3];   /* reflectance (diffuse), tint (mirror, glass), F0 (conductor), base colour (gltf); 0: does not reflect */
    uint kind;         /* CLP_MAT_* */
    float emission[3]; /* emitted radiance (W sr^-1 m^-2 per channel) */
    uint flags;        /* CLP_MATF_* */
    float roughness;   /* conductor, dielectric, gltf: GGX alpha = roughness^2; 0 = smooth */
    float ior;         /* dielectric, gltf: index of refraction inside / outside */
    float metallic;    /* gltf: conductor weight */
    uint pad0;
} Material;

/* The rest of a material: texture maps, coverage and the glTF layers
 * (clear coat, transmission), one record per material in a buffer of its own
 * (parallel to the materials). Only kernels compiled with textures
 * (CLP_HAS_TEXTURES), alpha cut-outs (CLP_HAS_ALPHA), a clear coat
 * (CLP_HAS_CLEARCOAT) or transmission (CLP_HAS_TRANSMISSION) read it; for a
 * scene with none of them the host uploads one zero record, and
 * FrameParams.scene_flags lacks CLP_SCENE_MATERIAL_EXT. */
typedef struct {
    int texture[8];     /* CLP_TEX_* slots: index into the texture descriptors, or CLP_NO_TEXTURE */
    float alpha;        /* coverage factor (base colour alpha), see alpha_mode */
    uint alpha_mode;    /* CLP_ALPHA_* */
    float alpha_cutoff;
    float normal_scale; /* normal map: scales the tangent-space x and y */
    float clearcoat;    /* gltf: weight of the clear coat (KHR_materials_clearcoat); 0: none */
    float clearcoat_roughness;    /* the coat's GGX alpha = clearcoat_roughness^2 */
    float clearcoat_normal_scale; /* the coat's normal map: scales the tangent-space x and y */
    float transmission; /* gltf: share of the dielectric base's diffuse lobe that transmits (KHR_materials_transmission) */
} MaterialExt;

/* One texture in the texel buffer: width x height texels from `offset` (in
 * uints; a float texel takes 4), row 0 at the top (v = 0), with its addressing. */
typedef struct {
    uint offset;
    uint width;
    uint height;
    uint flags; /* CLP_TEXF_* and the wrap modes */
} TextureDesc;

/* One light of the light table (see CLP_LIGHT_*). */
typedef struct {
    float a[3];
    uint type;
    float b[3];
    uint flags;
    float c[3];
    float cos_outer;
    float L[3];
    float cos_inner;
} Light;

/* Walker's alias table over the lights (Vose's construction on the host):
 * pick i uniformly, keep it with probability prob, else take alias. pmf is the
 * light's own selection probability, for MIS weights. */
typedef struct {
    float prob;
    uint alias;
    float pmf;
    uint pad;
} AliasEntry;

/* One node of the light BVH (docs/light-bvh.md; Conty Estevez and Kulla 2018),
 * 32 bytes, in depth-first order: an interior node's first child follows it.
 * Bounds are quantised, outwards, in the frame of the whole tree (the host's
 * LightBvh.origin and scale); the cone and the axis are widened by their own
 * quantisation error, so a node's bounds always contain its lights'. */
typedef struct {
    uint qbounds[3]; /* per axis: the quantised lower bound in bits 0-15, the upper in bits 16-31 */
    uint axis;       /* the cone's axis, octahedral, 16 bits a coordinate */
    float power;     /* phi: the lights' summed power */
    uint cones;      /* cos theta_o in bits 0-14, cos theta_e in bits 15-29 (both over [-1, 1]), two-sided bit 30 */
    uint child;      /* interior: the second child's index; leaf: the light's index in the light table */
    uint flags;      /* CLP_LIGHT_BVH_LEAF */
} LightBvhNode;
#define CLP_LIGHT_BVH_LEAF 1u
#define CLP_LIGHT_BVH_TWO_SIDED (1u << 30)

/* Camera, already turned into a ray basis by the host:
 * direction(x_ndc, y_ndc) = forward + x_ndc * right + y_ndc * up,
 * where forward is a unit vector and right and up are scaled by tan(fov/2)
 * of their axis. A thin lens (lens_radius > 0) focuses on the plane
 * focus_distance along forward; lens_radius 0 is a pinhole. Orthographic
 * (orthographic != 0, never with a lens): every ray has direction forward and
 * starts at eye + x_ndc * right + y_ndc * up, right and up scaled by the
 * half-extents. */
typedef struct {
    float eye[3];
    uint width;
    float forward[3];
    uint height;
    float right[3];
    float lens_radius;    /* world units; 0: pinhole (focus_distance unused) */
    float up[3];
    float focus_distance; /* world units along forward, > 0 with a lens */
    uint orthographic;
    uint pad0, pad1, pad2;
} CameraData;

/* What one launch of the path kernel needs besides the buffers. */
typedef struct {
    CameraData camera;
    uint seed;
    uint first_sample;     /* sample index of this launch's first sample */
    uint samples;          /* samples per pixel in this launch */
    uint rr_rule;          /* CLP_RR_* */
    uint rr_min_depth;     /* bounces before throughput roulette starts */
    uint pixel_offset;     /* first pixel of this launch (launches may cover a band) */
    uint pixel_count;
    uint light_count;      /* entries in the light table */
    uint env_light;        /* the environment's index in the light table, or CLP_NO_LIGHT */
    float ao_distance;     /* ambient occlusion ray length */
    float depth_scale;     /* depth view: distance that maps to 1 */
    float env_color[3];    /* constant environment radiance (no image) */
    uint env_width;        /* equirectangular image size; 0 without an image */
    float env_scale;       /* multiplies the image */
    float env_rot_cos;     /* rotation of the environment about +y */
    float env_rot_sin;
    uint env_height;
    uint scene_flags;      /* CLP_SCENE_*: what the scene really has, for kernels compiled with every feature */
    uint attr_stride;      /* floats per triangle in the attribute buffer (CLP_SCENE_UVS, _TANGENTS, _COLORS) */
    uint adaptive;         /* 1: adaptive sampling; only pixels whose `active` byte is set take samples, and the
                              film's w lanes sum r+g+b of odd-indexed samples (render/adaptive.hpp) */
    uint pad2, pad3;
    /* The light BVH (CLP_LIGHT_BVH; docs/light-bvh.md): the frame its nodes'
     * bounds are quantised in (world = origin + q * scale), its node count (0:
     * no finite light) and the number of infinite lights, picked uniformly. */
    float lbvh_origin[3];
    uint lbvh_node_count;
    float lbvh_scale[3];
    uint lbvh_infinite_count;
} FrameParams;

/* Counters the kernels bump with atomics; the host reads and clears them per launch. */
typedef struct {
    uint rays;      /* every ray traced, camera, bounce and shadow */
    uint nonfinite; /* samples that came out NaN or infinite (and were dropped) */
    uint pad0;
    uint pad1;
} Counters;

/* Running per-pixel sum, Kahan-compensated so that a float sum of a million
 * samples does not drift (Kahan 1965): sum holds the total, comp the lost
 * low-order part. The w lanes are zero, except under adaptive sampling
 * (FrameParams.adaptive), where they hold the compensated sum of r+g+b over
 * the pixel's odd-indexed samples: the second half film the noise estimate
 * compares with the whole. The sample count is kept by the host. */
typedef struct {
    float sum[4];
    float comp[4];
} AccumPixel;

/* One ray of a ray-batch benchmark (clpath bench rays): the batch kernels
 * read these, so loading rays is part of the measured time, as in other
 * GPU traversal benchmarks. tmax bounds the hit distance in units of |d|. */
typedef struct {
    float o[3];
    float tmax;
    float d[3];
    uint src; /* the primary ray a secondary ray starts from; for primaries, its own index */
} BatchRay;

/* A ray's hit, as traversal returns it and the closest-hit batch kernel
 * stores it: tri indexes the leaf-ordered triangles (TriVerts), -1 for a
 * miss; b1 and b2 are the barycentric weights of v1 and v2. */
typedef struct {
    float t;
    float b1, b2;
    int tri;
#if defined(__OPENCL_C_VERSION__) && defined(CLP_HAS_INSTANCES)
    int inst; /* kernels only: the node index of the hit instance's record (Instance), -1 for none */
#endif
} Hit;

/* The wavefront integrator's queue lengths (kernels/wavefront.cl): the paths
 * queued for this bounce, those queued for the next, the shadow rays, the
 * paths of this bounce queued to scatter. */
#define CLP_WF_QUEUED 0u
#define CLP_WF_NEXT 1u
#define CLP_WF_SHADOWS 2u
#define CLP_WF_SCATTER 3u
#define CLP_WF_COUNT_SLOTS 4u

/* The scene's device buffers, in the order every kernel that reads the scene
 * takes them: the one list behind the kernels' parameters (CLP_SCENE_PARAMS)
 * and the host's uploads and bindings (host/render/device_scene.hpp).
 * X(element type in the kernels, parameter name); AccelNode is the node type
 * of the layout a program traverses (kernels/traverse.cl). */
#define CLP_SCENE_BUFFERS(X)                                                              \
    X(AccelNode, nodes) X(TriVerts, tris) X(uint, tri_material) X(Material, materials)    \
    X(MaterialExt, material_ext) X(float, normals) X(Light, lights) X(AliasEntry, alias) \
    X(float4, env_pixels) X(float, env_cdf) X(float, attrs) X(TextureDesc, tex_desc)     \
    X(uint, texels) X(LightBvhNode, light_bvh) X(uint, light_trails) X(uint, light_infinite)
#ifndef __cplusplus
#define CLP_SCENE_PARAM(type, name) global const type* name,
#define CLP_SCENE_PARAMS CLP_SCENE_BUFFERS(CLP_SCENE_PARAM)
#endif

CLP_STATIC_ASSERT(sizeof(BvhNode64) == 64, bvh_node_is_64_bytes);
CLP_STATIC_ASSERT(sizeof(TriVerts) == 48, tri_verts_is_48_bytes);
CLP_STATIC_ASSERT(sizeof(Bvh4Node128) == 128, bvh4_node_is_128_bytes);
CLP_STATIC_ASSERT(sizeof(Bvh8Node256) == 256, bvh8_node_is_256_bytes);
CLP_STATIC_ASSERT(__builtin_offsetof(Bvh8Node256, hi_z) == 160 && __builtin_offsetof(Bvh8Node256, child) == 192 &&
                      __builtin_offsetof(Bvh8Node256, count) == 224,
                  bvh8_node_rows);
CLP_STATIC_ASSERT(__builtin_offsetof(Bvh4Node128, hi_z) == 80 && __builtin_offsetof(Bvh4Node128, child) == 96 &&
                      __builtin_offsetof(Bvh4Node128, count) == 112,
                  bvh4_node_rows);
/* Traversal reads nodes and triangles as float4 rows (kernels/traverse_*.cl):
 * each row's fourth field sits at offset 12 of its 16 bytes. */
CLP_STATIC_ASSERT(__builtin_offsetof(BvhNode64, child0) == 12 && __builtin_offsetof(BvhNode64, count0) == 28 &&
                      __builtin_offsetof(BvhNode64, lo1) == 32 && __builtin_offsetof(BvhNode64, child1) == 44 &&
                      __builtin_offsetof(BvhNode64, count1) == 60,
                  bvh_node_rows);
CLP_STATIC_ASSERT(__builtin_offsetof(TriVerts, v1) == 16 && __builtin_offsetof(TriVerts, v2) == 32,
                  tri_verts_rows);
CLP_STATIC_ASSERT(sizeof(Material) == 48, material_is_48_bytes);
CLP_STATIC_ASSERT(sizeof(MaterialExt) == 64, material_ext_is_64_bytes);
CLP_STATIC_ASSERT(sizeof(((MaterialExt*)0)->texture) == CLP_TEX_SLOTS * sizeof(int), material_ext_texture_slots);
CLP_STATIC_ASSERT(sizeof(TextureDesc) == 16, texture_desc_is_16_bytes);
CLP_STATIC_ASSERT(sizeof(CameraData) == 80, camera_is_80_bytes);
CLP_STATIC_ASSERT(sizeof(FrameParams) == 208, frame_params_is_208_bytes);
CLP_STATIC_ASSERT(sizeof(Light) == 64, light_is_64_bytes);
CLP_STATIC_ASSERT(sizeof(AliasEntry) == 16, alias_entry_is_16_bytes);
CLP_STATIC_ASSERT(sizeof(LightBvhNode) == 32, light_bvh_node_is_32_bytes);
CLP_STATIC_ASSERT(sizeof(Counters) == 16, counters_is_16_bytes);
CLP_STATIC_ASSERT(sizeof(AccumPixel) == 32, accum_pixel_is_32_bytes);
CLP_STATIC_ASSERT(sizeof(BatchRay) == 32, batch_ray_is_32_bytes);
#if !(defined(__OPENCL_C_VERSION__) && defined(CLP_HAS_INSTANCES))
CLP_STATIC_ASSERT(sizeof(Hit) == 16, hit_is_16_bytes);
#endif
CLP_STATIC_ASSERT(sizeof(Instance) == 128 && sizeof(Instance) == sizeof(Bvh4Node128), instance_is_one_node);
CLP_STATIC_ASSERT(__builtin_offsetof(Instance, world_to_object) == 48 && __builtin_offsetof(Instance, blas_root) == 96,
                  instance_rows);

#endif
