/* What every node layout's walk shares (traverse.cl): the leaf test and the
 * empty hit. */
#ifndef CLP_TRAVERSE_LEAF_CL
#define CLP_TRAVERSE_LEAF_CL

#include "common.h"
#include "intersect.cl"
#include "textures.cl"

/* The triangles first..first+count-1 against the ray, nearest hit kept in
 * *hit; returns whether one was found, at the first one when stop_at_first
 * (a constant at each call, so folded). TriVerts are rows of four 4-byte
 * fields at 16-byte offsets (shared_structs.h asserts it), so one aligned
 * float4 load fetches a vertex. Inlined at every site: a call inside the
 * walk makes a CPU save and reload the ray's vector registers around it (all
 * caller-saved in the x86-64 ABI), and four inlined copies in traverse_tree
 * traced 1.05x the primary and 1.02x the diffuse rays per second of one
 * out-of-line copy on PoCL (bunny, room:1003542); GPU compilers inline it
 * anyway. */
__attribute__((always_inline)) static inline int leaf_hits(const RayPre* r, global const TriVerts* tris,
                                                          uint first,
                                                          uint count, Hit* hit, int stop_at_first CLP_ALPHA_PARAM) {
    int found = 0;
    for (uint i = first; i < first + count; ++i) {
        global const float4* tv = (global const float4*)&tris[i];
        float t, b1, b2;
        if (intersect_triangle(r, tv[0].xyz, tv[1].xyz, tv[2].xyz, hit->t, &t, &b1, &b2)) {
#ifdef CLP_HAS_ALPHA
            if (!alpha_keeps_hit(alpha, tris[i].prim, b1, b2, r)) continue; /* a cut-out: as if not there (textures.cl) */
#endif
            hit->t = t;
            hit->b1 = b1;
            hit->b2 = b2;
            hit->tri = (int)i;
            found = 1;
            if (stop_at_first) return 1;
        }
    }
    return found;
}

/* No hit yet: the search interval ends at tmax. */
static inline void no_hit(Hit* hit, float tmax) {
    hit->t = tmax;
    hit->tri = -1;
    hit->b1 = hit->b2 = 0.0f;
}

/* How a walk (CLP_WALK, common.h) hands back its hit:
 *   CLP_WALK CLP_WALK_RESULT walk(CLP_WALK_OUT args...) { ... CLP_WALK_RETURN(hit); }
 *   CLP_WALK_ASSIGN(&hit) walk(CLP_WALK_OUT_ARG(&hit) args...);
 * (not one variadic macro: NVIDIA's OpenCL C compiler refuses variadic macros, as OpenCL C 1.2 allows)
 * On a CPU it returns it: PoCL keeps the walk out of line, and returned in
 * registers the hit made bunny's primary rays 1.1x faster than written
 * through a pointer (bench rays --ab-kernels, paired). On a GPU the walk is
 * inlined and writes through a pointer: a function returning a struct does so
 * through a hidden noalias pointer, and LLVM inlining it declares an alias
 * scope (llvm.experimental.noalias.scope.decl) that Oclgrind 21.10 cannot run,
 * so the kernels could not be created there. (traverse_bvh and the other
 * functions that fill a struct take the pointer in every shape.) */
#ifdef CLP_TARGET_GPU
#define CLP_WALK_RESULT void
#define CLP_WALK_OUT Hit *walk_out,
#define CLP_WALK_RETURN(h)                                                      \
    do {                                                                        \
        *walk_out = (h);                                                        \
        return;                                                                 \
    } while (0)
#define CLP_WALK_ASSIGN(out)
#define CLP_WALK_OUT_ARG(out) out,
#else
#define CLP_WALK_RESULT Hit
#define CLP_WALK_OUT
#define CLP_WALK_RETURN(h) return (h)
#define CLP_WALK_ASSIGN(out) *(out) =
#define CLP_WALK_OUT_ARG(out)
#endif


#endif
