/* Device entry points the robustness tests need beyond tests/kernels/probes.cl:
 * rays generated on the device (ten million of them need no host memory) and
 * traced through the renderer's own traversal. */
#ifndef CLP_ROBUSTNESS_PROBES_CL
#define CLP_ROBUSTNESS_PROBES_CL

#include "rng.cl"
#include "traverse.cl"

/* Watertightness: ray i aims at target (i % target_count), a vertex or a point
 * on an edge of a closed mesh. Variant j = i / target_count picks an origin: a
 * point of the inner ball (centre c, radius r; variant 0 and 1: c itself, so
 * that rays towards axis-aligned targets have exact +-0 direction components).
 * Even variants start inside and aim at the target: they must hit the mesh.
 * Odd variants start outside, beyond the target on the line from the inner
 * point, and aim at it: they must hit the mesh no further than the target plus
 * margin (a hit on the far side means the ray slipped through the near side).
 * Leaks are counted; the first leaking ray's index is kept. */
kernel void probe_watertight(global const AccelNode* nodes, global const TriVerts* tris, global const float* targets,
                             uint target_count, float cx, float cy, float cz, float radius, float margin,
                             ulong first, uint count, uint seed, global uint* leaks, global ulong* first_leak) {
    uint g = get_global_id(0);
    if (g >= count) return;
    ulong i = first + g;
    uint t = (uint)(i % target_count);
    uint j = (uint)(i / target_count);
    float3 target = vload3(t, targets);
    float3 c = (float3)(cx, cy, cz);
    if (j >= 2) {
        Rng r = rng_seed(j, t, seed);
        float3 u = (float3)(rng_next(&r), rng_next(&r), rng_next(&r)) * 2.0f - 1.0f;
        c += u * (radius * 0.57735f); /* a cube inside the ball */
    }
    float3 o, d;
    float expect;
    if ((j & 1u) == 0u) {
        o = c;
        d = normalize(target - c);
        expect = INFINITY;
    } else {
        o = target + 1.5f * (target - c);
        d = normalize(target - o);
        expect = length(target - o) + margin;
    }
    RayPre rp = ray_prepare(o, d);
    Hit h;
    traverse_bvh(&h, nodes, tris, &rp, INFINITY, 0, 0);
    if (h.tri < 0 || !(h.t <= expect)) {
        if (atomic_inc(leaks) == 0u) *first_leak = i;
    }
}

#endif
