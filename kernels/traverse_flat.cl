/* The thesis renderer's flat list of object boxes (host/bvh/flat.hpp), in
 * BvhNode64 records: the baseline the BVH is measured against, walked in a
 * program built with -DCLP_ACCEL_FLAT (traverse.cl).
 * Included by traverse.cl, which defines CLP_LAYOUT_* and picks the layout. */
#ifndef CLP_TRAVERSE_FLAT_CL
#define CLP_TRAVERSE_FLAT_CL

#include "traverse_leaf.cl"

#ifdef CLP_LAYOUT_FLAT

typedef BvhNode64 AccelNode;

/* The flat list: every record's two object boxes are tested, in order, and
 * a box entered before the closest hit so far has all its triangles tested.
 * The list ends at the first slot whose child is not a leaf. Same contract as
 * traverse_bvh (traverse.cl). */
#ifndef CLP_TARGET_GPU
CLP_WALK CLP_WALK_RESULT traverse_flat(CLP_WALK_OUT global const BvhNode64* nodes,
                                       global const TriVerts* tris, const RayPre* r, float tmax,
                                       int any_hit, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    for (int i = 0;; ++i) {
        global const BvhNode64* n = &nodes[i];
        if (visits) ++*visits;
        if (n->child0 >= 0) break;
        if (intersect_box(r, load3g(n->lo0), load3g(n->hi0), hit.t) < INFINITY &&
            leaf_hits(r, tris, (uint)~n->child0, n->count0, &hit, 0 CLP_ALPHA_ARG) && any_hit)
            break;
        if (n->child1 >= 0) break;
        if (intersect_box(r, load3g(n->lo1), load3g(n->hi1), hit.t) < INFINITY &&
            leaf_hits(r, tris, (uint)~n->child1, n->count1, &hit, 0 CLP_ALPHA_ARG) && any_hit)
            break;
    }
    CLP_WALK_RETURN(hit);
}
#else
/* On a GPU each slot is one iteration, read as the record's two float4 rows
 * (box and child, box and count): the same boxes and triangles in the same
 * order, with one box test and one leaf test in the loop. The two slots
 * written out each inlined a leaf test and took 70-72 registers at sm_90. */
CLP_WALK CLP_WALK_RESULT traverse_flat(CLP_WALK_OUT global const BvhNode64* nodes,
                                       global const TriVerts* tris, const RayPre* r, float tmax,
                                       int any_hit, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    global const float4* rows = (global const float4*)nodes;
    for (uint k = 0;; ++k) {
        if (visits && !(k & 1u)) ++*visits;
        const float4 lo = rows[2 * k], hi = rows[2 * k + 1];
        const int child = as_int(lo.w);
        if (child >= 0) break;
        if (intersect_box(r, lo.xyz, hi.xyz, hit.t) < INFINITY &&
            leaf_hits(r, tris, (uint)~child, as_uint(hi.w), &hit, 0 CLP_ALPHA_ARG) && any_hit)
            break;
    }
    CLP_WALK_RETURN(hit);
}
#endif

CLP_GPU_INLINE void accel_closest_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                     const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) traverse_flat(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, 0, visits CLP_ALPHA_ARG);
}

CLP_GPU_INLINE void accel_any_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                 const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) traverse_flat(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, 1, visits CLP_ALPHA_ARG);
}

#endif
#endif
