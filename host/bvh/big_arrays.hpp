#pragma once
// The BVH builder's large arrays (records, nodes, output), backed by
// transparent huge pages where Linux gives them on request
// (/sys/kernel/mm/transparent_hugepage/enabled = madvise, as on Debian): a
// build over millions of triangles writes hundreds of MiB of fresh memory,
// and with 4 KiB pages a good share of its time goes to page faults.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace clpath::bvh_build {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

// Asks for huge pages over the whole 2 MiB pages inside [p, p + bytes), which
// must not have been touched yet. Advice only: nothing happens where it is
// not supported or refused.
inline void advise_huge_pages(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHugePage - 1);
    if (end > first) madvise(reinterpret_cast<void*>(first), end - first, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

struct FreeDelete {
    void operator()(void* p) const { std::free(p); }
};
template <class T>
using BigArray = std::unique_ptr<T[], FreeDelete>;

// n uninitialised T's; from one huge page up, aligned to huge pages and advised to use them.
template <class T>
BigArray<T> big_array(std::size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
    const std::size_t bytes = std::max<std::size_t>(n * sizeof(T), 1);
    void* p = nullptr;
    if (bytes >= kHugePage) {
        p = std::aligned_alloc(kHugePage, (bytes + kHugePage - 1) / kHugePage * kHugePage);
        if (p) advise_huge_pages(p, bytes);
    } else {
        p = std::malloc(bytes);
    }
    if (!p) throw std::bad_alloc();
    return BigArray<T>(static_cast<T*>(p));
}

}  // namespace clpath::bvh_build
