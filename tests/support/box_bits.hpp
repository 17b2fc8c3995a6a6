#pragma once
// The BVH builder's boxes compared bit for bit (x, y, z of lo and hi; lane 3
// ignored): the builder's paths must agree to the sign of a zero, which an
// equality of values would not see (-0 == +0).
#include <cstring>

#include "bvh/build_simd.hpp"

namespace clpath::test {

inline bool same_box_bits(const bvh_build::Box4& a, const bvh_build::Box4& b) {
    alignas(16) float x[8], y[8];
    bvh_build::store4(x, a.lo);
    bvh_build::store4(x + 4, a.hi);
    bvh_build::store4(y, b.lo);
    bvh_build::store4(y + 4, b.hi);
    for (int i : {0, 1, 2, 4, 5, 6})
        if (std::memcmp(&x[i], &y[i], 4) != 0) return false;
    return true;
}

}  // namespace clpath::test
