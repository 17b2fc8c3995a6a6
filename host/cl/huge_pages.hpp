#pragma once
// Memory a CPU device reads in place, on 2 MiB pages. PoCL keeps a buffer's
// contents in ordinary 4 KiB pages (malloc), and a walk over a BVH of
// millions of triangles then misses the TLB at nearly every node it visits;
// a buffer made with CL_MEM_USE_HOST_PTR on this memory is read where it is,
// and Linux backs it with transparent huge pages (madvise(MADV_HUGEPAGE),
// honoured where /sys/kernel/mm/transparent_hugepage/enabled is "madvise" or
// "always", Debian's default being "madvise").
#include <cstddef>

namespace clpath {

// Buffers at least this large are worth it (one huge page).
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// A copy of `bytes` bytes of `data` in fresh memory aligned to a huge page
// and advised to be backed by huge pages, or nullptr when it cannot be had
// (the caller then lets the device copy as before). Free with free_huge_copy.
void* huge_copy(const void* data, std::size_t bytes);
void free_huge_copy(void* p) noexcept;

}  // namespace clpath
