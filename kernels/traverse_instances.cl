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
 * range read back when it pops (traverse_bvh4.cl's GPU walk), so the loop
 * has one leaf site and one instance-entry site. Included by traverse.cl. */
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

/* The ray of RayPre r in the object space of the instance whose record is
 * rows m (world_to_object in rows 3, 4, 5). */
static inline RayPre instance_ray(global const float4* m, const RayPre* world) {
    return ray_prepare(xform_point(m[3], m[4], m[5], world->org), xform_dir(m[3], m[4], m[5], world->dir));
}

/* Two lanes sorted, the leaf entries riding along in child (traverse_bvh4.cl's CLP_SORT2_DC). */
#define CLP_SORT2_INST(i, j, sw)                                                \
    if (d.s##j < d.s##i) {                                              \
        d = d.sw;                                                               \
        child = child.sw;                                                       \
    }

CLP_WALK CLP_WALK_RESULT instances_walk(CLP_WALK_OUT global const Bvh4Node128* nodes,
                                        global const TriVerts* tris, const RayPre* world, float tmax,
                                        int any_hit, uint* visits CLP_ALPHA_PARAM) {
    Hit hit;
    no_hit(&hit, tmax);
    hit.inst = -1;
    int stack[CLP_INSTANCE_STACK];
    int sp = 0;
    int entry = 0;
    int inst = -1;    /* the instance being walked (its record's node index), -1 in the top level */
    int inst_sp = 0;  /* the stack depth on entering it */
    RayPre r = *world;
    RayBox4 rb = ray_box4(&r);
    for (;;) {
        if (entry >= 0) {
            global const float4* n = (global const float4*)&nodes[entry];
            if (visits) ++*visits;
            float4 d = node_entry4(&rb, &r, r.inv_dir_finite, n, hit.t);
            int4 child = as_int4(n[6]);
            d = select(d, (float4)(INFINITY), child == 0); /* empty slots */
            child = select(child, ~(entry * 4 + (int4)(0, 1, 2, 3)), child < 0);
            if (any_hit) {
                int4 in = d < hit.t;
                if (in.s0 && child.s0 > 0) stack[sp++] = child.s0;
                if (in.s1 && child.s1 > 0) stack[sp++] = child.s1;
                if (in.s2 && child.s2 > 0) stack[sp++] = child.s2;
                if (in.s3 && child.s3 > 0) stack[sp++] = child.s3;
                if (in.s0 && child.s0 < 0) stack[sp++] = child.s0;
                if (in.s1 && child.s1 < 0) stack[sp++] = child.s1;
                if (in.s2 && child.s2 < 0) stack[sp++] = child.s2;
                if (in.s3 && child.s3 < 0) stack[sp++] = child.s3;
            } else {
                CLP_SORT4(CLP_SORT2_INST)
                if (d.s3 < hit.t) stack[sp++] = child.s3;
                if (d.s2 < hit.t) stack[sp++] = child.s2;
                if (d.s1 < hit.t) stack[sp++] = child.s1;
                if (d.s0 < hit.t) {
                    entry = child.s0;
                    continue;
                }
            }
        } else {
            const uint ref = (uint)~entry;
            global const Bvh4Node128* n = &nodes[ref >> 2];
            const int first = n->child[ref & 3u];
            if (inst < 0) {
                /* A top-level leaf: one instance. Its walk starts at its mesh's root. */
                inst = ~first;
                global const float4* m = (global const float4*)&nodes[inst];
                r = instance_ray(m, world);
                rb = ray_box4(&r);
                inst_sp = sp;
                entry = (int)((global const Instance*)m)->blas_root;
                continue;
            }
            if (leaf_hits(&r, tris, (uint)~first, n->count[ref & 3u], &hit, any_hit CLP_ALPHA_ARG)) {
                hit.inst = inst;
                if (any_hit) break;
            }
        }
        if (inst >= 0 && sp == inst_sp) { /* the instance is done: back to the top level */
            inst = -1;
            r = *world;
            rb = ray_box4(&r);
        }
        if (sp == 0) break;
        entry = stack[--sp];
    }
    CLP_WALK_RETURN(hit);
}

#endif
#endif
