#pragma once
// The SAH builder's partitions (binned_builder.cpp): a node's records
// scattered into the other array, left side and right side, by the same
// centroid-to-bin test that binned them (BinMap), so each side gets exactly
// the binned counts. Each has a portable version and an AVX version chosen
// at run time where the CPU has AVX; the two agree bit for bit.
#include <cstdint>

#include "bvh/binning.hpp"

namespace clpath::bvh_build {

// Records [begin, end) of src into dst: those whose centroid's bin on axis
// is <= bin to the front, in order, the others to the back, in reverse order.
// Returns where the back starts; lcb, rcb: the two sides' centroid bounds.
// Without a branch per record, where an in-place partition mispredicts
// about every other record.
std::uint32_t partition_refs(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, const BinMap& map,
                             int axis, int bin, Box4& lcb, Box4& rcb);

// A stable partition of records [begin, end) of src: those whose centroid's
// bin on axis is <= bin to dst[left_at ...], the others to dst[right_at ...],
// both in order; writes nothing else of dst (a big node's chunks scatter at
// once into neighbouring ranges). For the big nodes: streaming stores. lcb, rcb: the two sides' centroid bounds.
void scatter_refs_stable(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at,
                         std::uint32_t right_at, const BinMap& map, int axis, int bin, Box4& lcb, Box4& rcb);

// The engine of both: the left cursor starts at left_at and steps forward,
// the right one starts at right_at and steps by right_step (1 or -1 as an
// unsigned). Returns the left cursor's end. Tests call both versions.
std::uint32_t partition_portable(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end,
                                 std::uint32_t left_at, std::uint32_t right_at, std::uint32_t right_step,
                                 const BinMap& map, int axis, int bin, Box4& lcb, Box4& rcb);
// Only where avx_available(). stream: with non-temporal stores (where dst
// is 32-byte aligned), for scatters far larger than the caches.
std::uint32_t partition_avx(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at,
                            std::uint32_t right_at, std::uint32_t right_step, const BinMap& map, int axis, int bin,
                            Box4& lcb, Box4& rcb, bool stream = false);

}  // namespace clpath::bvh_build
