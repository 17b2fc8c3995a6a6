#include "bench/cpu_traversal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clpath {
namespace {

struct D3 {
    double x, y, z;
};
D3 load(const float* p) { return {p[0], p[1], p[2]}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

struct Ray {
    D3 o, d;
    double tmax;
};

// Moller & Trumbore (1997), edges included so a ray through a shared edge hits.
bool hit_triangle(const Ray& r, const TriVerts& tv, double tmax, bool at_origin, double* t_out) {
    const D3 v0 = load(tv.v0), e1 = sub(load(tv.v1), v0), e2 = sub(load(tv.v2), v0);
    const D3 p = cross(r.d, e2);
    const double det = dot(e1, p);
    if (det == 0) return false;
    const double inv = 1 / det;
    const D3 s = sub(r.o, v0);
    const double u = dot(s, p) * inv;
    if (u < 0 || u > 1) return false;
    const D3 q = cross(s, e1);
    const double v = dot(r.d, q) * inv;
    if (v < 0 || u + v > 1) return false;
    const double t = dot(e2, q) * inv;
    if (!((at_origin ? t >= 0 : t > 0) && t < tmax)) return false;
    *t_out = t;
    return true;
}

// Entry distance of the ray into a box, or +inf. A widened exit (1e-9
// relative) keeps a ray that grazes a face from missing the box: visiting a
// box too many costs time, never a result.
double hit_box(const Ray& r, const float* lo, const float* hi, double tmax) {
    double tn = 0, tf = tmax;
    const double o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return std::numeric_limits<double>::infinity();
            continue;
        }
        double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
        if (t0 > t1) std::swap(t0, t1);
        tn = std::max(tn, t0);
        tf = std::min(tf, t1 * (1 + 1e-9) + 1e-300);
    }
    return tn <= tf ? tn : std::numeric_limits<double>::infinity();
}

// Depth-first over both children; any_hit stops at the first hit.
template <bool AnyHit>
CpuHit walk(const Bvh& bvh, const BatchRay& br, bool at_origin) {
    const Ray r{load(br.o), load(br.d), double(br.tmax)};
    CpuHit best;
    best.t = r.tmax;
    int stack[2 * CLP_BVH_MAX_DEPTH + 2];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const BvhNode64& n = bvh.nodes[std::size_t(stack[--sp])];
        for (int s = 0; s < 2; ++s) {
            const int child = s ? n.child1 : n.child0;
            const std::uint32_t count = s ? n.count1 : n.count0;
            if (child < 0 && count == 0) continue;
            if (!(hit_box(r, s ? n.lo1 : n.lo0, s ? n.hi1 : n.hi0, best.t) < best.t)) continue;
            if (child >= 0) {
                stack[sp++] = child;
                continue;
            }
            for (std::uint32_t i = std::uint32_t(~child); i < std::uint32_t(~child) + count; ++i) {
                double t;
                if (hit_triangle(r, bvh.triangles[i], best.t, at_origin, &t)) {
                    best.t = t;
                    best.prim = bvh.triangles[i].prim;
                    if (AnyHit) return best;
                }
            }
        }
    }
    return best;
}

}  // namespace

CpuHit cpu_closest_hit(const Bvh& bvh, const BatchRay& ray, bool at_origin) { return walk<false>(bvh, ray, at_origin); }
std::int64_t cpu_any_hit(const Bvh& bvh, const BatchRay& ray) { return walk<true>(bvh, ray, false).prim; }

}  // namespace clpath
