/* The 4-wide BVH (shared_structs.h, Bvh4Node128), the layout clpath
 * traverses unless a program asks for another (traverse.cl): a stack of
 * CLP_BVH4_STACK entries (enough for the deepest tree the builder and the
 * widening allow), nearest child first for the closest hit
 * (traverse_tree), leaves first for any hit (occlude_tree). Nodes hold
 * their four children's boxes, so each step tests four boxes from one
 * 128-byte fetch.
 * Programs for GPUs (-DCLP_TARGET_GPU) walk the closest hit another way,
 * shaped for their registers (traverse_tree below); the any-hit walk is
 * the same for both.
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

/* One compare-exchange of a sorting network: lanes i < j of d end in
 * ascending order, child and count following their distance. */
#define CLP_SORT2(i, j, sw)                                                     \
    if (d.s##j < d.s##i) {                                                      \
        d = d.sw;                                                               \
        child = child.sw;                                                       \
        count = count.sw;                                                       \
    }
/* The five exchanges that sort four lanes (Knuth TAOCP vol. 3, 5.3.4). */
#define CLP_SORT4(SORT2)                                                        \
    SORT2(0, 1, s1023)                                                          \
    SORT2(2, 3, s0132)                                                          \
    SORT2(0, 2, s2103)                                                          \
    SORT2(1, 3, s0321)                                                          \
    SORT2(1, 2, s0213)

#ifndef CLP_TARGET_GPU
/* Closest hit, after the sort: the children entered before the closest hit
 * so far are a prefix of the slots, so each test of a slot is nested in its
 * nearer neighbour's and the first slot entered beyond the hit ends the
 * tests. A leaf is intersected at once; an interior child is pushed (but the
 * nearest, walked next). */
#define CLP_SORTED_LEAF(k)                                                      \
    if (child.s##k < 0) leaf_hits(r, tris, (uint)~child.s##k, count.s##k, &hit, 0 CLP_ALPHA_ARG);
#define CLP_SORTED_PUSH(k)                                                      \
    if (child.s##k > 0) stack[sp++] = child.s##k;

/* Closest hit in (0, tmax). *visits (may be NULL) counts nodes fetched, for
 * the traversal heat map and benchmarks.
 *
 * Each step fetches one 128-byte Bvh4Node128 as eight float4 rows and tests its
 * four boxes in one vector slab test. The children are sorted by entry
 * distance (a five-exchange sorting network, Knuth TAOCP vol. 3, 5.3.4), the
 * leaves among them intersected nearest first, the nearest interior one
 * walked next and the others pushed farthest first. */
CLP_WALK CLP_WALK_RESULT traverse_tree(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                       global const TriVerts* tris, const RayPre* r, float tmax,
                                       uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    /* Node indices only: keeping each entry distance too, to drop nodes
     * entered beyond a hit found after the push, cost more than it saved
     * (bunny, PoCL) and doubles the private memory. */
    int stack[CLP_BVH4_STACK];
    int sp = 0;
    int node = 0;
    const RayBox4 rb = ray_box4(r);
    const int finite = r->inv_dir_finite;
    for (;;) {
        global const float4* n = (global const float4*)&nodes[node];
        if (visits) ++*visits;
        float4 d = node_entry4(&rb, r, finite, n, hit.t);
        int4 child = as_int4(n[6]);
        uint4 count = as_uint4(n[7]);
        d = select(d, (float4)(INFINITY), child == 0); /* empty slots */
        CLP_SORT4(CLP_SORT2)
        if (d.s0 < hit.t) {
            CLP_SORTED_LEAF(0)
            if (d.s1 < hit.t) {
                CLP_SORTED_LEAF(1)
                if (d.s2 < hit.t) {
                    CLP_SORTED_LEAF(2)
                    if (d.s3 < hit.t) CLP_SORTED_LEAF(3)
                }
            }
            /* Again, against the hit the leaves may have found. */
            if (d.s0 < hit.t) {
                if (d.s1 < hit.t) {
                    if (d.s2 < hit.t) {
                        if (d.s3 < hit.t) CLP_SORTED_PUSH(3)
                        CLP_SORTED_PUSH(2)
                    }
                    CLP_SORTED_PUSH(1)
                }
                /* The nearest interior child is walked next, not pushed and popped. */
                if (child.s0 > 0) {
                    node = child.s0;
                    continue;
                }
            }
        }
        if (sp == 0) break;
        node = stack[--sp];
    }
    CLP_WALK_RETURN(hit);
}

#else
/* Two lanes sorted, the leaf entries riding along in child. */
#define CLP_SORT2_DC(i, j, sw)                                                  \
    if (d.s##j < d.s##i) {                                                      \
        d = d.sw;                                                               \
        child = child.sw;                                                       \
    }

/* Closest hit in (0, tmax) on a GPU: the same boxes and triangles in the same
 * arithmetic, in another order. A leaf is pushed as ~(node * 4 + slot), its
 * range read back from the node when it pops (as occlude_tree does), so the
 * children are sorted with their leaves and the nearest, leaf or interior, is
 * taken next without a push, the others pushed farthest first. The loop then
 * has one leaf site, and while a leaf's triangles are tested nothing of the
 * node is live: the CPU walk's four inlined leaf tests under the sorted
 * lanes took 87-95 registers at sm_90, this one 64 or fewer (the budget an
 * SM needs to keep 32 warps; benchmarks/results/gpu-compile/).
 * Leaves that a nearer leaf's hit puts beyond reach are still tested (their
 * pushes came first), so a triangle hit at exactly the closest distance from
 * two leaves may be reported from the other one than on a CPU; the distance
 * is the same. */
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
#endif

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

CLP_GPU_INLINE void accel_closest_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                     const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) traverse_tree(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
}

CLP_GPU_INLINE void accel_any_hit(Hit* hit, global const AccelNode* nodes, global const TriVerts* tris,
                                 const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    CLP_WALK_ASSIGN(hit) occlude_tree(CLP_WALK_OUT_ARG(hit) nodes, tris, r, tmax, visits CLP_ALPHA_ARG);
}

#endif
#endif
