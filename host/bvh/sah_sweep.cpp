#include "bvh/sah_sweep.hpp"

#include <limits>

namespace clpath::bvh_build {

// Right side costs swept from the right into an array, then the left side
// swept and each boundary priced as it is reached.
void sah_sweep(const Bins& bins, int a, const BinList& list, std::uint32_t n, float& best_cost, int& best_axis,
               int& best_bin) {
    float right_cost[kMaxBins];
    const int m = list.size;
    const Box4* box = bins.box[a];
    const std::uint32_t* count = bins.count[a];
    F4 lo = splat(std::numeric_limits<float>::infinity()), hi = splat(-std::numeric_limits<float>::infinity());
    std::uint32_t cnt = 0;
    for (int j = m - 1; j > 0; --j) {  // right side areas, swept from the right
        lo = min4(lo, box[j].lo);
        hi = max4(hi, box[j].hi);
        cnt += count[j];
        right_cost[j] = cnt ? area_of_extent(hi - lo) * float(cnt) : 0.0f;
    }
    lo = splat(std::numeric_limits<float>::infinity());
    hi = splat(-std::numeric_limits<float>::infinity());
    cnt = 0;
    for (int j = 0; j < m - 1; ++j) {
        lo = min4(lo, box[j].lo);
        hi = max4(hi, box[j].hi);
        cnt += count[j];
        if (cnt == 0 || cnt == n) continue;
        const float c = area_of_extent(hi - lo) * float(cnt) + right_cost[j + 1];
        if (c < best_cost) {
            best_cost = c;
            best_axis = a;
            best_bin = list.bin[j];
        }
    }
}

}  // namespace clpath::bvh_build
