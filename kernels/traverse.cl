/* Traversal of the scene's acceleration structure. traverse_bvh() is what
 * the integrator and the ray-batch kernels call. A program holds one node
 * layout, each in a file of its own that defines AccelNode (the record the
 * kernels receive), accel_closest_hit() and accel_any_hit() (traverse_bvh's
 * contract, without any_hit):
 *   traverse_bvh4.cl  the 4-wide BVH (Bvh4Node128), what GPU programs and
 *                     instanced scenes walk;
 *   traverse_bvh8.cl  with -DCLP_NODES_BVH8, the 8-wide BVH (Bvh8Node256),
 *                     what CPU programs walk (host: node_layout,
 *                     render/kernel_programs.hpp);
 *   traverse_flat.cl  with -DCLP_ACCEL_FLAT, the thesis renderer's flat list
 *                     of object boxes in BvhNode64 records (host/bvh/flat.hpp),
 *                     the baseline the BVH is measured against.
 * With CLP_HAS_INSTANCES (a scene that places meshes by instances) the
 * 4-wide BVH is two levels, walked by traverse_instances.cl.
 * A new layout is a new file beside them, included and selected below.
 * What every layout shares (the leaf test, the empty hit) is in
 * traverse_leaf.cl.
 * With CLP_HAS_ALPHA every function takes the alpha scene as a last
 * argument (CLP_ALPHA_PARAM, textures.cl) and skips cut-out hits. */
#ifndef CLP_TRAVERSE_CL
#define CLP_TRAVERSE_CL

#include "common.h"
#include "intersect.cl"
#include "textures.cl"
#include "traverse_leaf.cl"

/* The layout this program walks: exactly one CLP_LAYOUT_* is defined, and
 * each layout file compiles only under its own. */
#if defined(CLP_ACCEL_FLAT)
#define CLP_LAYOUT_FLAT
#elif defined(CLP_NODES_BVH8)
#define CLP_LAYOUT_BVH8
#else
#define CLP_LAYOUT_BVH4
#endif

#include "traverse_bvh4.cl"
#include "traverse_bvh8.cl"
#include "traverse_flat.cl"

/* The wide layouts name their walks alike: traverse_tree (closest hit) and
 * occlude_tree (any hit). */
#if defined(CLP_LAYOUT_BVH4) || defined(CLP_LAYOUT_BVH8)
CLP_GPU_INLINE void accel_closest_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                     const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) traverse_tree(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
}

CLP_GPU_INLINE void accel_any_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                 const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) occlude_tree(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
}
#endif
#ifdef CLP_HAS_INSTANCES
#ifndef CLP_LAYOUT_BVH4
#error "instances are walked in the 4-wide BVH only (-DCLP_HAS_INSTANCES without -DCLP_ACCEL_FLAT or -DCLP_NODES_BVH8)"
#endif
#include "traverse_instances.cl"
#endif

/* The hit of a ray in (0, tmax), written to *hit: the closest, or with
 * any_hit (shadow rays) the first found; tri -1 for none. *visits (may be
 * NULL) counts nodes fetched. Forced inline on a GPU, as the walks: with
 * the alpha test in the leaf clang kept it out of line, and the ray, the hit
 * and the walk's stack went through the GPU's stack (wf_trace: 87 registers,
 * 544 B at sm_90; inlined, 72 and 248). */
CLP_GPU_INLINE void traverse_bvh(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                const RayPre* r, float tmax, int any_hit, uint* visits CLP_ALPHA_PARAM) {
#ifdef CLP_HAS_INSTANCES
    /* Two levels (traverse_instances.cl); hit->inst names the instance. */
    if (any_hit)
        CLP_WALK_ASSIGN(hit) instances_walk(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, 1, visits CLP_ALPHA_ARG);
    else
        CLP_WALK_ASSIGN(hit) instances_walk(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, 0, visits CLP_ALPHA_ARG);
#else
    if (any_hit)
        accel_any_hit(hit, nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
    else
        accel_closest_hit(hit, nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
#endif
}

#endif
