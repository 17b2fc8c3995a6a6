/* The 8-wide BVH (shared_structs.h, Bvh8Node256), what CPU programs walk
 * (-DCLP_NODES_BVH8, traverse.cl): eight boxes per 256-byte node in one
 * float8 slab test, as Embree walks 8-wide nodes on AVX CPUs (Wald et al.
 * 2014, "Embree: a kernel framework for efficient CPU ray tracing"). The
 * box arithmetic is intersect_box4's lane for lane, so a box is entered at
 * the same distance as in the 4-wide walk.
 * Closest hit: the leaves a node's boxes admit are tested at once, in slot
 * order; the nearest interior child is walked next and the others pushed
 * with their entry distance, and a pop skips an entry the hit has moved
 * closer than (Embree keeps distances on its stack likewise). Sorting eight
 * lanes would take 19 compare-exchanges a node (Knuth TAOCP vol. 3, 5.3.4),
 * each a branch on PoCL.
 * Any hit: as occlude_tree of the 4-wide walk, interior children pushed
 * first and leaves last, so the leaves pop first; a leaf is pushed as
 * ~(node * 8 + slot) and its range read back from the node when it pops.
 * Included by traverse.cl, which defines CLP_LAYOUT_* and picks the layout. */
#ifndef CLP_TRAVERSE_BVH8_CL
#define CLP_TRAVERSE_BVH8_CL

#include "traverse_leaf.cl"

#ifdef CLP_LAYOUT_BVH8

typedef Bvh8Node256 AccelNode;
/* intersect.cl's min and max by compare and select (it undefines them after use). */
#define CLP_MIN8(a, b) select((b), (a), (a) < (b))
#define CLP_MAX8(a, b) select((b), (a), (a) > (b))

/* What the box test reads of the ray at every node, broadcast once per walk
 * (as RayBox4: read through RayPre, it was loaded again at every node). */
typedef struct {
    float8 ox, oy, oz;
    float8 ix, iy, iz;
    int near_x, near_y, near_z, finite;
} RayBox8;

static inline RayBox8 ray_box8(const RayPre* r) {
    RayBox8 b;
    b.ox = (float8)(r->org.x);
    b.oy = (float8)(r->org.y);
    b.oz = (float8)(r->org.z);
    b.ix = (float8)(r->inv_dir.x);
    b.iy = (float8)(r->inv_dir.y);
    b.iz = (float8)(r->inv_dir.z);
    b.near_x = r->near_x;
    b.near_y = r->near_y;
    b.near_z = r->near_z;
    b.finite = r->inv_dir_finite;
    return b;
}

/* slab_entry4 on eight lanes: entry distance, or +INFINITY for a miss. */
static inline float8 slab_entry8(float8 nx, float8 ny, float8 nz, float8 fx, float8 fy, float8 fz, float tmax) {
    float8 tnear = CLP_MAX8(nx, CLP_MAX8(ny, CLP_MAX8(nz, (float8)(0.0f))));
    float8 tfar = CLP_MIN8(fx, CLP_MIN8(fy, CLP_MIN8(fz, (float8)(tmax)))) * (1.0f + 2.0f * CLP_GAMMA(5));
    return select((float8)(INFINITY), tnear, tnear <= tfar);
}

/* The entry distances of a node's eight boxes: intersect_box4_ordered where
 * 1/dir is finite, else intersect_box4's NaN repair, lane for lane. */
__attribute__((always_inline)) static inline float8 node_entry8(const RayBox8* b, global const float8* n, float tmax) {
    if (b->finite)
        return slab_entry8((n[b->near_x] - b->ox) * b->ix, (n[b->near_y] - b->oy) * b->iy, (n[b->near_z] - b->oz) * b->iz,
                           (n[b->near_x ^ 1] - b->ox) * b->ix, (n[b->near_y ^ 1] - b->oy) * b->iy,
                           (n[b->near_z ^ 1] - b->oz) * b->iz, tmax);
    float8 t0x = (n[0] - b->ox) * b->ix, t1x = (n[1] - b->ox) * b->ix;
    float8 t0y = (n[2] - b->oy) * b->iy, t1y = (n[3] - b->oy) * b->iy;
    float8 t0z = (n[4] - b->oz) * b->iz, t1z = (n[5] - b->oz) * b->iz;
    t0x = select(t0x, -t1x, isnan(t0x));
    t1x = select(t1x, -t0x, isnan(t1x));
    t0y = select(t0y, -t1y, isnan(t0y));
    t1y = select(t1y, -t0y, isnan(t1y));
    t0z = select(t0z, -t1z, isnan(t0z));
    t1z = select(t1z, -t0z, isnan(t1z));
    return slab_entry8(CLP_MIN8(t0x, t1x), CLP_MIN8(t0y, t1y), CLP_MIN8(t0z, t1z), CLP_MAX8(t0x, t1x), CLP_MAX8(t0y, t1y),
                       CLP_MAX8(t0z, t1z), tmax);
}

#define CLP_LANES8(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7)

/* Closest hit in (0, tmax); *visits (may be NULL) counts nodes fetched. */
CLP_WALK CLP_WALK_RESULT traverse_tree(CLP_WALK_OUT global const Bvh8Node256* nodes, global const TriVerts* tris,
                                       const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_BVH8_STACK];
    float sdist[CLP_BVH8_STACK];
    int sp = 0;
    int node = 0;
    const RayBox8 rb = ray_box8(r);
    for (;;) {
        global const float8* n = (global const float8*)&nodes[node];
        if (visits) ++*visits;
        float8 d = node_entry8(&rb, n, hit.t);
        const int8 child = as_int8(n[6]);
        const uint8 count = as_uint8(n[7]);
#define CLP_LEAF8(k)                                                            \
    if (child.s##k < 0 && d.s##k < hit.t) leaf_hits(r, tris, (uint)~child.s##k, count.s##k, &hit, 0 CLP_ALPHA_ARG);
        CLP_LANES8(CLP_LEAF8)
        int next = 0;
        float best = hit.t;
#define CLP_INNER8(k)                                                           \
    if (child.s##k > 0 && d.s##k < hit.t) {                                     \
        if (d.s##k < best) {                                                    \
            if (next > 0) {                                                     \
                stack[sp] = next;                                               \
                sdist[sp++] = best;                                             \
            }                                                                   \
            next = child.s##k;                                                  \
            best = d.s##k;                                                      \
        } else {                                                                \
            stack[sp] = child.s##k;                                             \
            sdist[sp++] = d.s##k;                                               \
        }                                                                       \
    }
        CLP_LANES8(CLP_INNER8)
        if (next > 0) {
            node = next;
            continue;
        }
        for (;;) {
            if (sp == 0) CLP_WALK_RETURN(hit);
            --sp;
            if (sdist[sp] < hit.t) break;
        }
        node = stack[sp];
    }
}

/* Any hit in (0, tmax), for shadow rays: returns at the first hit found. */
CLP_WALK CLP_WALK_RESULT occlude_tree(CLP_WALK_OUT global const Bvh8Node256* nodes, global const TriVerts* tris,
                                      const RayPre* r, float tmax, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_BVH8_STACK];
    int sp = 0;
    int entry = 0;
    const RayBox8 rb = ray_box8(r);
    for (;;) {
        if (entry >= 0) {
            global const float8* n = (global const float8*)&nodes[entry];
            if (visits) ++*visits;
            const float8 d = node_entry8(&rb, n, hit.t);
            const int8 child = as_int8(n[6]);
            const int8 in = d < hit.t;
#define CLP_PUSH_INNER8(k) if (in.s##k && child.s##k > 0) stack[sp++] = child.s##k;
#define CLP_PUSH_LEAF8(k) if (in.s##k && child.s##k < 0) stack[sp++] = ~(entry * 8 + k);
            CLP_LANES8(CLP_PUSH_INNER8)
            CLP_LANES8(CLP_PUSH_LEAF8)
        } else {
            const uint ref = (uint)~entry;
            global const Bvh8Node256* n = &nodes[ref >> 3];
            if (leaf_hits(r, tris, (uint)~n->child[ref & 7u], n->count[ref & 7u], &hit, 1 CLP_ALPHA_ARG)) break;
        }
        if (sp == 0) break;
        entry = stack[--sp];
    }
    CLP_WALK_RETURN(hit);
}

#undef CLP_MIN8
#undef CLP_MAX8
#endif
#endif
