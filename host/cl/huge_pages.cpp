#include "cl/huge_pages.hpp"

#include <cstdlib>
#include <cstring>

#include <sys/mman.h>

namespace clpath {

void* huge_copy(const void* data, std::size_t bytes) {
    const std::size_t size = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = std::aligned_alloc(kHugePageBytes, size);
    if (!p) return nullptr;
    // Advice only: where the kernel declines, the memory is ordinary pages.
    (void)madvise(p, size, MADV_HUGEPAGE);
    std::memcpy(p, data, bytes);
    return p;
}

void free_huge_copy(void* p) noexcept { std::free(p); }

}  // namespace clpath
