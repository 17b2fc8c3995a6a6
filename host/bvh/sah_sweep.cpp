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

void sah_sweep_all_bins(const Bins& bins, int nbins, const bool sweep[3], std::uint32_t n, float& best_cost,
                        int& best_axis, int& best_bin) {
    // cost[a][j]: the boundary after bin j; +inf where one side is empty
    // (never below best_cost, so never chosen: as sah_sweep's skip).
    float right_cost[3][kMaxBins], cost[3][kMaxBins];
    const float inf = std::numeric_limits<float>::infinity();
    F4 lo[3], hi[3];
    std::uint32_t cnt[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
        lo[a] = splat(inf);
        hi[a] = splat(-inf);
    }
    for (int j = nbins - 1; j > 0; --j)
        for (int a = 0; a < 3; ++a) {
            lo[a] = min4(lo[a], bins.box[a][j].lo);
            hi[a] = max4(hi[a], bins.box[a][j].hi);
            cnt[a] += bins.count[a][j];
            right_cost[a][j] = cnt[a] ? area_of_extent(hi[a] - lo[a]) * float(cnt[a]) : 0.0f;
        }
    for (int a = 0; a < 3; ++a) {
        lo[a] = splat(inf);
        hi[a] = splat(-inf);
        cnt[a] = 0;
    }
    for (int j = 0; j < nbins - 1; ++j)
        for (int a = 0; a < 3; ++a) {
            lo[a] = min4(lo[a], bins.box[a][j].lo);
            hi[a] = max4(hi[a], bins.box[a][j].hi);
            cnt[a] += bins.count[a][j];
            const float c = area_of_extent(hi[a] - lo[a]) * float(cnt[a]) + right_cost[a][j + 1];
            cost[a][j] = cnt[a] == 0 || cnt[a] == n ? inf : c;
        }
    for (int a = 0; a < 3; ++a)
        if (sweep[a])
            for (int j = 0; j < nbins - 1; ++j)
                if (cost[a][j] < best_cost) {
                    best_cost = cost[a][j];
                    best_axis = a;
                    best_bin = j;
                }
}

}  // namespace clpath::bvh_build
