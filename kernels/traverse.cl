/* Traversal of the scene's acceleration structure. traverse_bvh() is what
 * the integrator and the ray-batch kernels call; it walks the BVH, or, in a
 * program built with -DCLP_ACCEL_FLAT, the thesis renderer's flat list of
 * object boxes (host/bvh/flat.hpp), the baseline the BVH is measured against.
 *
 * BVH traversal: a stack of CLP_BVH_MAX_DEPTH entries (the builder guarantees
 * no deeper tree), nearest child first. Nodes hold both children's boxes
 * (Aila & Laine 2009), so each step tests two boxes from one 64-byte fetch. */
#ifndef CLP_TRAVERSE_CL
#define CLP_TRAVERSE_CL

#include "common.h"
#include "intersect.cl"

inline int intersect_leaf(const RayPre* r, global const TriVerts* tris, uint first, uint count, Hit* hit) {
    int found = 0;
    for (uint i = first; i < first + count; ++i) {
        global const TriVerts* tv = &tris[i];
        float t, b1, b2;
        if (intersect_triangle(r, load3g(tv->v0), load3g(tv->v1), load3g(tv->v2), hit->t, &t, &b1, &b2)) {
            hit->t = t;
            hit->b1 = b1;
            hit->b2 = b2;
            hit->tri = (int)i;
            found = 1;
        }
    }
    return found;
}

/* Closest hit in (0, tmax). *visits (may be NULL) counts nodes fetched, for
 * the traversal heat map and benchmarks. When any_hit is set, returns at the
 * first hit found (shadow rays): the compiler folds it for constant arguments. */
inline Hit traverse_tree(global const BvhNode* nodes, global const TriVerts* tris, const RayPre* r, float tmax,
                         int any_hit, uint* visits) {
    Hit hit;
    hit.t = tmax;
    hit.tri = -1;
    hit.b1 = hit.b2 = 0.0f;
    int stack[CLP_BVH_MAX_DEPTH];
    int sp = 0;
    int node = 0;
    for (;;) {
        global const BvhNode* n = &nodes[node];
        if (visits) ++*visits;
        float t0 = intersect_box(r, load3g(n->lo0), load3g(n->hi0), hit.t);
        float t1 = intersect_box(r, load3g(n->lo1), load3g(n->hi1), hit.t);
        int c0 = n->child0, c1 = n->child1;
        /* Leaves are intersected at once; only interior children are descended. */
        if (t0 < INFINITY && c0 < 0) {
            if (intersect_leaf(r, tris, (uint)~c0, n->count0, &hit) && any_hit) return hit;
            t0 = INFINITY;
        }
        if (t1 < INFINITY && c1 < 0) {
            if (intersect_leaf(r, tris, (uint)~c1, n->count1, &hit) && any_hit) return hit;
            t1 = INFINITY;
        }
        /* A leaf hit may have shortened hit.t; a child entered beyond it is pruned. */
        int go0 = t0 < hit.t, go1 = t1 < hit.t;
        if (go0 && go1) {
            int near = t0 <= t1 ? c0 : c1;
            stack[sp++] = t0 <= t1 ? c1 : c0;
            node = near;
        } else if (go0) {
            node = c0;
        } else if (go1) {
            node = c1;
        } else {
            if (sp == 0) break;
            node = stack[--sp];
        }
    }
    return hit;
}

/* The flat list: every record's two object boxes are tested, in order, and
 * a box entered before the closest hit so far has all its triangles tested.
 * The list ends at the first slot whose child is not a leaf. Same contract as
 * traverse_tree. */
inline Hit traverse_flat(global const BvhNode* nodes, global const TriVerts* tris, const RayPre* r, float tmax,
                         int any_hit, uint* visits) {
    Hit hit;
    hit.t = tmax;
    hit.tri = -1;
    hit.b1 = hit.b2 = 0.0f;
    for (int i = 0;; ++i) {
        global const BvhNode* n = &nodes[i];
        if (visits) ++*visits;
        if (n->child0 >= 0) break;
        if (intersect_box(r, load3g(n->lo0), load3g(n->hi0), hit.t) < INFINITY &&
            intersect_leaf(r, tris, (uint)~n->child0, n->count0, &hit) && any_hit)
            return hit;
        if (n->child1 >= 0) break;
        if (intersect_box(r, load3g(n->lo1), load3g(n->hi1), hit.t) < INFINITY &&
            intersect_leaf(r, tris, (uint)~n->child1, n->count1, &hit) && any_hit)
            return hit;
    }
    return hit;
}

inline Hit traverse_bvh(global const BvhNode* nodes, global const TriVerts* tris, const RayPre* r, float tmax,
                        int any_hit, uint* visits) {
#ifdef CLP_ACCEL_FLAT
    return traverse_flat(nodes, tris, r, tmax, any_hit, visits);
#else
    return traverse_tree(nodes, tris, r, tmax, any_hit, visits);
#endif
}

#endif
