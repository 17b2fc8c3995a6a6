// Large read-only buffers on a CPU device are read in place from memory on
// huge pages (host/cl/huge_pages.hpp, Context::buffer): the copy is exact and
// aligned, the device reads it back unchanged, and CLPATH_HUGE_PAGES=0 keeps
// the device's own copy.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <vector>

#include "cl/context.hpp"
#include "cl/huge_pages.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

std::vector<std::uint32_t> counting(std::size_t n) {
    std::vector<std::uint32_t> v(n);
    std::iota(v.begin(), v.end(), 7u);
    return v;
}

cl_mem_flags flags_of(const Buffer& b) {
    cl_mem_flags f = 0;
    EXPECT_EQ(clGetMemObjectInfo(b.get(), CL_MEM_FLAGS, sizeof f, &f, nullptr), CL_SUCCESS);
    return f;
}

std::vector<std::uint32_t> read_back(Context& ctx, const Buffer& b, std::size_t n) {
    std::vector<std::uint32_t> out(n, 0);
    ctx.read(b, out);
    return out;
}

}  // namespace

TEST(HugePages, TheCopyIsExactAndOnAHugePageBoundary) {
    const auto data = counting(3 * kHugePageBytes / 4 + 5);  // not a whole number of pages
    void* p = huge_copy(data.data(), data.size() * 4);
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes, 0u);
    EXPECT_EQ(std::memcmp(p, data.data(), data.size() * 4), 0);
    free_huge_copy(p);
}

TEST(HugePages, ALargeReadOnlyBufferIsReadInPlaceAndReadsBackUnchanged) {
    Context& ctx = test::device();
    if (!ctx.device().is_cpu) GTEST_SKIP() << "not a CPU device";
    const auto data = counting(kHugePageBytes / 4 + 3);
    {
        Buffer b = ctx.buffer(data.size() * 4, CL_MEM_READ_ONLY, "large", data.data());
        EXPECT_NE(flags_of(b) & CL_MEM_USE_HOST_PTR, 0u);
        void* host = nullptr;
        ASSERT_EQ(clGetMemObjectInfo(b.get(), CL_MEM_HOST_PTR, sizeof host, &host, nullptr), CL_SUCCESS);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(host) % kHugePageBytes, 0u);
        EXPECT_EQ(read_back(ctx, b, data.size()), data);
    }
    // Control: small buffers, writable ones and the switch keep the device's copy.
    const auto small = counting(1000);
    Buffer s = ctx.buffer(small.size() * 4, CL_MEM_READ_ONLY, "small", small.data());
    EXPECT_EQ(flags_of(s) & CL_MEM_USE_HOST_PTR, 0u);
    EXPECT_EQ(read_back(ctx, s, small.size()), small);
    Buffer w = ctx.buffer(data.size() * 4, CL_MEM_READ_WRITE, "writable", data.data());
    EXPECT_EQ(flags_of(w) & CL_MEM_USE_HOST_PTR, 0u);
    ::setenv("CLPATH_HUGE_PAGES", "0", 1);  // read when a context is made
    Context switched_off(ctx.device());
    ::unsetenv("CLPATH_HUGE_PAGES");
    Buffer off = switched_off.buffer(data.size() * 4, CL_MEM_READ_ONLY, "switched off", data.data());
    EXPECT_EQ(flags_of(off) & CL_MEM_USE_HOST_PTR, 0u);
    EXPECT_EQ(read_back(switched_off, off, data.size()), data);
}

TEST(HugePages, ABadSwitchIsRefusedWhenAContextIsMade) {
    ::setenv("CLPATH_HUGE_PAGES", "2", 1);
    EXPECT_THROW(Context c(test::device().device()), UsageError);
    ::unsetenv("CLPATH_HUGE_PAGES");
}
