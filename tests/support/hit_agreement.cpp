#include "support/hit_agreement.hpp"

#include "support/traversal_probes.hpp"

namespace clpath::test {

bool same_hit_or_exact_tie(const BvhTriangles& tris, const TestRay& ray, int prim_a, int prim_b, float t) {
    if (prim_a == prim_b) return true;
    if (prim_a < 0 || prim_b < 0) return false;
    const std::vector<float> r = packed({ray});
    for (int p : {prim_a, prim_b})
        if (trace_brute({tris[std::size_t(p)]}, r).t[0] != t) return false;
    return true;
}

}  // namespace clpath::test
