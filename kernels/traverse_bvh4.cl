/* The 4-wide BVH (shared_structs.h, Bvh4Node128), the layout GPU programs
 * and instanced scenes walk (CPU programs walk the 8-wide one,
 * traverse_bvh8.cl; traverse.cl picks): a stack of CLP_BVH4_STACK entries
 * (enough for the deepest tree the builder and the widening allow), nearest
 * child first for the closest hit (traverse_tree), leaves first for any hit
 * (occlude_tree). Nodes hold their four children's boxes, so each step tests
 * four boxes from one 128-byte fetch. The closest-hit walk is shaped for a
 * GPU's registers (below); it is plain OpenCL C, and the tests run it on
 * PoCL too.
 * Included by traverse.cl, which defines CLP_LAYOUT_* and picks the layout. */
#ifndef CLP_TRAVERSE_BVH4_CL
#define CLP_TRAVERSE_BVH4_CL

#include "traverse_leaf.cl"

#ifdef CLP_LAYOUT_BVH4

typedef Bvh4Node128 AccelNode;

/* The entry distances of a Bvh4Node128's four child boxes (rows n), or
 * +INFINITY for each missed; the ordered test where 1/dir is finite. Forced
 * inline, as leaf_hits: with two callers PoCL kept it out of line, and both
 * walks lost 8 to 14 % of their speed to the call. */
__attribute__((always_inline)) static inline float4 node_entry4(const RayBox4* rb, const RayPre* r, int finite,
                                                                global const float4* n, float tmax) {
    return finite ? intersect_box4_ordered(rb, n, tmax) : intersect_box4(r, n[0], n[1], n[2], n[3], n[4], n[5], tmax);
}

/* The five exchanges that sort four lanes (Knuth TAOCP vol. 3, 5.3.4). */
#define CLP_SORT4(SORT2)                                                        \
    SORT2(0, 1, s1023)                                                          \
    SORT2(2, 3, s0132)                                                          \
    SORT2(0, 2, s2103)                                                          \
    SORT2(1, 3, s0321)                                                          \
    SORT2(1, 2, s0213)

/* Two lanes sorted, the leaf entries riding along in child. */
#define CLP_SORT2_DC(i, j, sw)                                                  \
    if (d.s##j < d.s##i) {                                                      \
        d = d.sw;                                                               \
        child = child.sw;                                                       \
    }

/* Closest hit in (0, tmax), shaped for a GPU: the same boxes and triangles in
 * the same arithmetic as a sorted walk, in another order. A leaf is pushed as ~(node * 4 + slot), its
 * range read back from the node when it pops (as occlude_tree does), so the
 * children are sorted with their leaves and the nearest, leaf or interior, is
 * taken next without a push, the others pushed farthest first. The loop then
 * has one leaf site, and while a leaf's triangles are tested nothing of the
 * node is live: a walk with four inlined leaf tests under the sorted lanes
 * (what CPUs ran before the 8-wide layout) took 87-95 registers at sm_90,
 * this one 64 or fewer (the budget an
 * SM needs to keep 32 warps; benchmarks/results/gpu-compile/).
 * Leaves that a nearer leaf's hit puts beyond reach are still tested (their
 * pushes came first), so a triangle hit at exactly the closest distance from
 * two leaves may be reported from the other one than by the CPU reference;
 * the distance is the same. */
CLP_WALK CLP_WALK_RESULT traverse_tree(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                       global const TriVerts* tris, const RayPre* r, float tmax,
                                       uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_BVH4_STACK];
    int sp = 0;
    int entry = 0;
    const RayBox4 rb = ray_box4(r);
    const int finite = r->inv_dir_finite;
    for (;;) {
        if (entry >= 0) {
            global const float4* n = (global const float4*)&nodes[entry];
            if (visits) ++*visits;
            float4 d = node_entry4(&rb, r, finite, n, hit.t);
            int4 child = as_int4(n[6]);
            d = select(d, (float4)(INFINITY), child == 0); /* empty slots */
            child = select(child, ~(entry * 4 + (int4)(0, 1, 2, 3)), child < 0);
            CLP_SORT4(CLP_SORT2_DC)
            if (d.s3 < hit.t) stack[sp++] = child.s3;
            if (d.s2 < hit.t) stack[sp++] = child.s2;
            if (d.s1 < hit.t) stack[sp++] = child.s1;
            if (d.s0 < hit.t) {
                entry = child.s0;
                continue;
            }
        } else {
            const uint ref = (uint)~entry;
            global const Bvh4Node128* n = &nodes[ref >> 2];
            leaf_hits(r, tris, (uint)~n->child[ref & 3u], n->count[ref & 3u], &hit, 0 CLP_ALPHA_ARG);
        }
        if (sp == 0) break;
        entry = stack[--sp];
    }
    CLP_WALK_RETURN(hit);
}

/* Any hit in (0, tmax), for shadow rays: returns at the first hit found,
 * which need not be the closest; same contract otherwise as traverse_tree.
 * The children entered are pushed unsorted, interior ones first and leaves
 * last, so the leaves pop first (one may end the walk); a leaf is pushed as
 * ~(node * 4 + slot) and its range read back from the node when it pops.
 * The loop then has a single leaf site: 1.11x the shadow rays per second on
 * PoCL (bunny) of testing each slot's leaf before the pushes, both inlined.
 * The closest hit keeps that order (traverse_tree), as the hit its leaves
 * find culls the pushes: with its leaves on the stack too it traced fewer
 * diffuse rays per second. */
CLP_WALK CLP_WALK_RESULT occlude_tree(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                      global const TriVerts* tris, const RayPre* r, float tmax,
                                      uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_BVH4_STACK];
    int sp = 0;
    int entry = 0;
    const RayBox4 rb = ray_box4(r);
    const int finite = r->inv_dir_finite;
    for (;;) {
        if (entry >= 0) {
            global const float4* n = (global const float4*)&nodes[entry];
            if (visits) ++*visits;
            float4 d = node_entry4(&rb, r, finite, n, hit.t);
            int4 child = as_int4(n[6]);
            int4 in = d < hit.t;
            if (in.s0 && child.s0 > 0) stack[sp++] = child.s0;
            if (in.s1 && child.s1 > 0) stack[sp++] = child.s1;
            if (in.s2 && child.s2 > 0) stack[sp++] = child.s2;
            if (in.s3 && child.s3 > 0) stack[sp++] = child.s3;
            if (in.s0 && child.s0 < 0) stack[sp++] = ~(entry * 4);
            if (in.s1 && child.s1 < 0) stack[sp++] = ~(entry * 4 + 1);
            if (in.s2 && child.s2 < 0) stack[sp++] = ~(entry * 4 + 2);
            if (in.s3 && child.s3 < 0) stack[sp++] = ~(entry * 4 + 3);
        } else {
            const uint ref = (uint)~entry;
            global const Bvh4Node128* n = &nodes[ref >> 2];
            if (leaf_hits(r, tris, (uint)~n->child[ref & 3u], n->count[ref & 3u], &hit, 1 CLP_ALPHA_ARG)) break;
        }
        if (sp == 0) break;
        entry = stack[--sp];
    }
    CLP_WALK_RETURN(hit);
}

#endif
#endif
