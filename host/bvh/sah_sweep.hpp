#pragma once
// The SAH sweep of the binned builder (binned_builder.cpp): the cheapest
// split among one axis's bin boundaries (MacDonald & Booth 1990; Wald 2007).
#include <cstdint>

#include "bvh/binning.hpp"

namespace clpath::bvh_build {

// The cheapest boundary among list's bins on axis a: left area x left count
// plus right area x right count, not yet over the node's area (n: the node's
// triangles; a boundary with all or none on one side is no split). Where it
// is cheaper than best_cost, sets best_cost, best_axis = a and best_bin (the
// last bin on the left); the first of equal costs wins.
void sah_sweep(const Bins& bins, int a, const BinList& list, std::uint32_t n, float& best_cost, int& best_axis,
               int& best_bin);

// sah_sweep over all bins (0 .. bins - 1) of the axes a with sweep[a], in
// order a = 0, 1, 2: the same choice, bit for bit, with the three axes'
// sweeps interleaved (three independent chains of min and max, where one
// axis at a time waited on each step's result).
void sah_sweep_all_bins(const Bins& bins, int nbins, const bool sweep[3], std::uint32_t n, float& best_cost,
                        int& best_axis, int& best_bin);

}  // namespace clpath::bvh_build
