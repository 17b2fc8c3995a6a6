/* The two-level walk of an instanced scene (-DCLP_HAS_INSTANCES; the layout
 * in shared_structs.h, Instance): the top-level 4-wide BVH over the
 * instances' world boxes, and at each instance leaf the ray moved into the
 * instance's object space and walked down its mesh's bottom-level BVH, on
 * the same stack. When the stack falls back to the depth it had on entering
 * the instance, the walk is back in the top level and takes the world ray
 * again. The object-space direction is W d, not renormalised, so a hit's t
 * is the world ray's t and the closest hit so far culls both levels alike.
 * One walk serves the closest hit and any hit (any_hit is a constant at each
 * call site, so folded): children sorted nearest first for the closest hit,
 * leaves first for any hit; a leaf is pushed as ~(node * 4 + slot) and its
 * range read back when it pops (traverse_bvh4.cl's GPU walk), so each level's
 * loop has one leaf site. Here too: the instance's maps of points, normals
 * and hit points to world space, which the shading and the ray batches use.
 * Included by traverse.cl. */
#ifndef CLP_TRAVERSE_INSTANCES_CL
#define CLP_TRAVERSE_INSTANCES_CL

#include "traverse_leaf.cl"
#include "traverse_bvh4.cl"

#if defined(CLP_HAS_INSTANCES) && defined(CLP_LAYOUT_BVH4)

/* The affine map of rows r0, r1, r2 (m00 m01 m02 t0, ...) applied to a point
 * and to a direction (no translation). */
static inline float3 xform_point(float4 r0, float4 r1, float4 r2, float3 p) {
    return (float3)(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}
static inline float3 xform_dir(float4 r0, float4 r1, float4 r2, float3 d) {
    return (float3)(dot(r0.xyz, d), dot(r1.xyz, d), dot(r2.xyz, d));
}

/* An object-space normal in world space: the inverse transpose of the
 * object-to-world map applied, W^T n with W the world-to-object rows 3-5 of
 * the instance record im; unit (or zero for a zero n). For the geometric
 * normal too: a mirroring instance (det M < 0) reverses its triangles'
 * winding, so the cross product of the moved edges would point inside, but
 * a flattened copy has two corners swapped back (scene/scene_builder.cpp)
 * and keeps its outside as the front; W^T n is that normal, whatever det's
 * sign, and shading sees a mirrored instance as it sees its flattened copy. */
static inline float3 instance_normal(global const float4* im, float3 n) {
    return normalize3(n.x * im[3].xyz + n.y * im[4].xyz + n.z * im[5].xyz);
}

/* A direction on an instance's surface (a vertex tangent, dp/du) in world
 * space: moved by the object-to-world map's linear part, rows 0-2 of im. */
static inline float3 instance_dir(global const float4* im, float3 v) {
    return xform_dir(im[0], im[1], im[2], v);
}

/* -1 for a mirroring instance (det M < 0), else 1 (Instance.det_sign): the
 * sign its tangent frames' bitangents take in world space. The flattened
 * copy's corners are swapped back, which turns dp/du x dp/dv against its
 * normal, and a vertex tangent's bitangent is cross(n, t) w with n through
 * the inverse transpose: both flip with det M's sign (scene.hpp, moved_tangent). */
static inline float instance_handedness(global const float4* im) {
    return ((global const Instance*)im)->det_sign;
}

/* The hit point of barycentrics b1, b2 on the object-space triangle v0 v1 v2
 * of instance im, in world space, with its error bound. The vertices are
 * moved to world space first, so the point is interpolated exactly as on a
 * flattened copy (hit_point); each moved vertex is off its exact image by at
 * most gamma(4) (|M| |v| + |t|) per axis (four terms summed; PBR 3rd
 * ed., 3.9.4), and a convex combination of the vertices is off by at most
 * the largest of those, which is added to hit_point's bound. */
static inline float3 instance_hit_point(global const float4* im, float3 v0, float3 v1, float3 v2, float b1, float b2,
                                        float3* err) {
    const float4 r0 = im[0], r1 = im[1], r2 = im[2];
    const float3 a0 = fabs(r0.xyz), a1 = fabs(r1.xyz), a2 = fabs(r2.xyz);
    const float3 vmax = fmax(fabs(v0), fmax(fabs(v1), fabs(v2)));
    const float3 moved = CLP_GAMMA(4) * (float3)(dot(a0, vmax) + fabs(r0.w), dot(a1, vmax) + fabs(r1.w),
                                                 dot(a2, vmax) + fabs(r2.w));
    float3 p = hit_point(xform_point(r0, r1, r2, v0), xform_point(r0, r1, r2, v1), xform_point(r0, r1, r2, v2), b1,
                         b2, err);
    *err = (*err + moved) * (1.0f + CLP_GAMMA(2)); /* the sum itself rounded */
    return p;
}

/* Two lanes sorted, the leaf entries riding along in child (traverse_bvh4.cl's CLP_SORT2_DC). */
#define CLP_SORT2_INST(i, j, sw)                                                \
    if (d.s##j < d.s##i) {                                              \
        d = d.sw;                                                               \
        child = child.sw;                                                       \
    }

/* The pushes of one 4-wide node's children (entry distances d, child
 * entries child, leaves already as ~(node * 4 + slot)) for the walk at
 * either level: leaves last for any hit, farthest first for the closest hit,
 * whose nearest child is walked next (entry, then NEXT) rather than pushed. */
#define CLP_INSTANCE_PUSHES(NEXT)                                              \
    if (any_hit) {                                                              \
        int4 in = d < hit.t;                                                    \
        if (in.s0 && child.s0 > 0) stack[sp++] = child.s0;                      \
        if (in.s1 && child.s1 > 0) stack[sp++] = child.s1;                      \
        if (in.s2 && child.s2 > 0) stack[sp++] = child.s2;                      \
        if (in.s3 && child.s3 > 0) stack[sp++] = child.s3;                      \
        if (in.s0 && child.s0 < 0) stack[sp++] = child.s0;                      \
        if (in.s1 && child.s1 < 0) stack[sp++] = child.s1;                      \
        if (in.s2 && child.s2 < 0) stack[sp++] = child.s2;                      \
        if (in.s3 && child.s3 < 0) stack[sp++] = child.s3;                      \
    } else {                                                                    \
        CLP_SORT4(CLP_SORT2_INST)                                               \
        if (d.s3 < hit.t) stack[sp++] = child.s3;                               \
        if (d.s2 < hit.t) stack[sp++] = child.s2;                               \
        if (d.s1 < hit.t) stack[sp++] = child.s1;                               \
        if (d.s0 < hit.t) {                                                     \
            entry = child.s0;                                                   \
            NEXT;                                                               \
        }                                                                       \
    }

/* The children of node entry, tested against ray r (box rb): d and child. */
#define CLP_INSTANCE_NODE(rb, r)                                               \
    global const float4* n = (global const float4*)&nodes[entry];               \
    if (visits) ++*visits;                                                      \
    float4 d = node_entry4(&rb, &r, r.inv_dir_finite, n, hit.t);                \
    int4 child = as_int4(n[6]);                                                 \
    d = select(d, (float4)(INFINITY), child == 0); /* empty slots */            \
    child = select(child, ~(entry * 4 + (int4)(0, 1, 2, 3)), child < 0);

/* Slots below the walk's stack entries: the world ray's origin and
 * direction (bits), the instance of the closest hit so far, and the
 * instance walked now. They are read back from there (on leaving an
 * instance, on a hit) rather than kept in registers through the walk: kept,
 * wf_shadow took 79 registers at sm_90 and wf_trace 82 (in the two nested
 * loops of an earlier walk), stored, 64 and 71. */
#define CLP_INST_WORLD 0
#define CLP_INST_HIT 6
#define CLP_INST_NOW 7
#define CLP_INST_BASE 8
CLP_STATIC_ASSERT((CLP_INST_BASE + CLP_INSTANCE_STACK) * 4 <= 256, instance_walk_stack_within_256_bytes);

static inline float3 slot_float3(const int* s) {
    return (float3)(as_float(s[0]), as_float(s[1]), as_float(s[2]));
}

/* The slots as a walk starts: the world ray's bits, no hit's instance yet. */
static inline void slots_start(int* stack, const RayPre* world) {
    stack[CLP_INST_WORLD + 0] = as_int(world->org.x);
    stack[CLP_INST_WORLD + 1] = as_int(world->org.y);
    stack[CLP_INST_WORLD + 2] = as_int(world->org.z);
    stack[CLP_INST_WORLD + 3] = as_int(world->dir.x);
    stack[CLP_INST_WORLD + 4] = as_int(world->dir.y);
    stack[CLP_INST_WORLD + 5] = as_int(world->dir.z);
    stack[CLP_INST_HIT] = -1;
}

#ifndef CLP_TARGET_GPU
/* On a CPU the two levels are two loops, one inside the other: the top
 * level on the world ray until a leaf (one instance) comes up, then the
 * instance's mesh on the object-space ray until the stack is back at the
 * depth it had on entry. The world ray's RayPre is made again from its
 * origin and direction for each top-level stretch: *world is ray_prepare's
 * (every caller's), so the same bits. The nodes and leaves are visited in
 * the same order as by the GPU's one loop below, which traced 0.89x the
 * rays per second of this one on PoCL (bunnies:100, median of five). */
CLP_WALK CLP_WALK_RESULT instances_walk(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                        global const TriVerts* tris, const RayPre* world, float tmax,
                                        int any_hit, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_INST_BASE + CLP_INSTANCE_STACK];
    slots_start(stack, world);
    int sp = CLP_INST_BASE;
    int entry = 0;
    for (;;) {
        const float3 wo = slot_float3(stack + CLP_INST_WORLD), wd = slot_float3(stack + CLP_INST_WORLD + 3);
        {
            const RayPre r = ray_prepare(wo, wd);
            const RayBox4 rb = ray_box4(&r);
            while (entry >= 0) {
                CLP_INSTANCE_NODE(rb, r)
                CLP_INSTANCE_PUSHES(continue)
                if (sp == CLP_INST_BASE) {
                    hit.inst = stack[CLP_INST_HIT];
                    CLP_WALK_RETURN(hit);
                }
                entry = stack[--sp];
            }
        }
        /* A top-level leaf: one instance. Its walk starts at its mesh's root. */
        const int inst = ~nodes[(uint)~entry >> 2].child[(uint)~entry & 3u];
        global const float4* m = (global const float4*)&nodes[inst];
        const RayPre r = ray_prepare(xform_point(m[3], m[4], m[5], wo), xform_dir(m[3], m[4], m[5], wd));
        const RayBox4 rb = ray_box4(&r);
        const int base = sp;
        entry = (int)((global const Instance*)m)->blas_root;
        for (;;) {
            if (entry >= 0) {
                CLP_INSTANCE_NODE(rb, r)
                CLP_INSTANCE_PUSHES(continue)
            } else {
                const uint ref = (uint)~entry;
                global const Bvh4Node128* n = &nodes[ref >> 2];
                if (leaf_hits(&r, tris, (uint)~n->child[ref & 3u], n->count[ref & 3u], &hit, any_hit CLP_ALPHA_ARG)) {
                    stack[CLP_INST_HIT] = inst;
                    if (any_hit) {
                        hit.inst = inst;
                        CLP_WALK_RETURN(hit);
                    }
                }
            }
            if (sp == base) break;
            entry = stack[--sp];
        }
        if (sp == CLP_INST_BASE) break;
        entry = stack[--sp];
    }
    hit.inst = stack[CLP_INST_HIT];
    CLP_WALK_RETURN(hit);
}

#else
/* On a GPU one loop walks both levels: the ray it tests (r, rb) is the world ray in
 * the top level and the instance's object-space ray below it. Entering an
 * instance (a top-level leaf pops) remembers the stack depth (base); when the
 * walk would pop below it, the instance is done and the world ray is made
 * again from its slots (ray_prepare, as every caller made *world: the same
 * bits). Two nested loops, one per level, took 71 registers at sm_90 for
 * wf_trace (the top level's loop kept values live through the bottom
 * level's); one loop with one node site and one leaf site keeps one ray,
 * and took 64 (63 for wf_shadow) with intersect_box4_ordered's plane rows
 * from the signs of 1/dir. */
CLP_WALK CLP_WALK_RESULT instances_walk(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                        global const TriVerts* tris, const RayPre* world, float tmax,
                                        int any_hit, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    int stack[CLP_INST_BASE + CLP_INSTANCE_STACK];
    slots_start(stack, world);
    int sp = CLP_INST_BASE;
    int base = -1; /* the stack depth on entering the instance walked now; -1 in the top level */
    int entry = 0;
    RayPre r = *world;
    RayBox4 rb = ray_box4(&r);
    for (;;) {
        if (entry >= 0) {
            CLP_INSTANCE_NODE(rb, r)
            CLP_INSTANCE_PUSHES(continue)
        } else {
            const uint ref = (uint)~entry;
            global const Bvh4Node128* n = &nodes[ref >> 2];
            if (base < 0) {
                /* A top-level leaf: one instance. Its walk starts at its mesh's root. */
                const int inst = ~n->child[ref & 3u];
                stack[CLP_INST_NOW] = inst;
                global const float4* m = (global const float4*)&nodes[inst];
                const float3 wo = slot_float3(stack + CLP_INST_WORLD), wd = slot_float3(stack + CLP_INST_WORLD + 3);
                r = ray_prepare(xform_point(m[3], m[4], m[5], wo), xform_dir(m[3], m[4], m[5], wd));
                rb = ray_box4(&r);
                base = sp;
                entry = (int)((global const Instance*)m)->blas_root;
                continue;
            }
            if (leaf_hits(&r, tris, (uint)~n->child[ref & 3u], n->count[ref & 3u], &hit, any_hit CLP_ALPHA_ARG)) {
                stack[CLP_INST_HIT] = stack[CLP_INST_NOW];
                if (any_hit) {
                    hit.inst = stack[CLP_INST_NOW];
                    CLP_WALK_RETURN(hit);
                }
            }
        }
        if (sp == CLP_INST_BASE) break;
        if (sp == base) {
            /* The instance is done: back to the world ray. */
            r = ray_prepare(slot_float3(stack + CLP_INST_WORLD), slot_float3(stack + CLP_INST_WORLD + 3));
            rb = ray_box4(&r);
            base = -1;
        }
        entry = stack[--sp];
    }
    hit.inst = stack[CLP_INST_HIT];
    CLP_WALK_RETURN(hit);
}

#endif

#endif
#endif
