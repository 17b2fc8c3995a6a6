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

}  // namespace clpath::bvh_build
