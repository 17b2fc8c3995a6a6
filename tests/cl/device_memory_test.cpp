// Device memory accounting (host/cl/context.hpp): a Context counts the bytes
// of its live buffers, and a freed buffer gives its bytes back, so that a
// long-lived context (the viewer across resizes, a benchmark sweep) is not
// refused an allocation that fits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>

#include "cl/context.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

// Sets CLPATH_DEVICE_MEMORY_LIMIT for one test and removes it afterwards.
struct MemoryLimit {
    explicit MemoryLimit(std::size_t bytes) { ::setenv("CLPATH_DEVICE_MEMORY_LIMIT", std::to_string(bytes).c_str(), 1); }
    ~MemoryLimit() { ::unsetenv("CLPATH_DEVICE_MEMORY_LIMIT"); }
};

}  // namespace

TEST(DeviceMemory, FreeingGivesTheBytesBack) {
    Context& ctx = test::device();
    const std::size_t base = ctx.allocated_bytes();
    {
        Buffer a = ctx.buffer(1000, CL_MEM_READ_WRITE, "a");
        EXPECT_EQ(ctx.allocated_bytes(), base + 1000);
        Buffer b = ctx.buffer(3000, CL_MEM_READ_WRITE, "b");
        EXPECT_EQ(ctx.allocated_bytes(), base + 4000);
    }
    EXPECT_EQ(ctx.allocated_bytes(), base);
}

TEST(DeviceMemory, MovesCountEachBufferOnce) {
    Context& ctx = test::device();
    const std::size_t base = ctx.allocated_bytes();
    {
        Buffer a = ctx.buffer(1000, CL_MEM_READ_WRITE, "a");
        Buffer moved(std::move(a));
        EXPECT_EQ(a.get(), nullptr);
        EXPECT_EQ(a.bytes(), 0u);
        EXPECT_EQ(moved.bytes(), 1000u);
        EXPECT_EQ(ctx.allocated_bytes(), base + 1000);

        // Assigning over a live buffer frees that buffer at once.
        Buffer b = ctx.buffer(3000, CL_MEM_READ_WRITE, "b");
        EXPECT_EQ(ctx.allocated_bytes(), base + 4000);
        b = std::move(moved);
        EXPECT_EQ(ctx.allocated_bytes(), base + 1000);
        EXPECT_EQ(b.bytes(), 1000u);
        EXPECT_EQ(moved.get(), nullptr);

        // Assigning into an empty buffer frees nothing.
        Buffer empty;
        empty = std::move(b);
        EXPECT_EQ(ctx.allocated_bytes(), base + 1000);
        // Reassigning a fresh buffer replaces the old one's bytes.
        empty = ctx.buffer(500, CL_MEM_READ_WRITE, "c");
        EXPECT_EQ(ctx.allocated_bytes(), base + 500);
    }
    EXPECT_EQ(ctx.allocated_bytes(), base);
}

TEST(DeviceMemory, AllocatingAndFreeingFarMoreThanTheDeviceHasSucceeds) {
    // At the device's own sizes: each buffer a quarter of its global memory
    // (or its largest single allocation), sixteen times its global memory in all.
    Context& ctx = test::device();
    const DeviceInfo& d = ctx.device();
    const std::size_t chunk = std::min<std::size_t>(d.max_alloc, d.global_mem / 4);
    const std::size_t rounds = 16 * (d.global_mem / chunk);
    const std::size_t base = ctx.allocated_bytes();
    for (std::size_t i = 0; i < rounds; ++i) {
        Buffer b = ctx.buffer(chunk, CL_MEM_READ_WRITE, "round " + std::to_string(i));
        ASSERT_EQ(ctx.allocated_bytes(), base + chunk);
    }
    EXPECT_EQ(ctx.allocated_bytes(), base);
}

TEST(DeviceMemory, ManyBuffersUnderALimitFitWhenTheOldOnesAreFreed) {
    // The same with the device made to look small, as a viewer's film is
    // replaced on every resize: a thousand times the limit passes through,
    // never more than two films alive at once.
    // The copy of the Context's counter is its own, whatever the other tests did.
    const std::size_t limit = 1 << 20, film = limit / 5 * 2;  // two fit, three do not
    MemoryLimit small(limit);
    Context ctx(test::device().device());
    Buffer current = ctx.buffer(film, CL_MEM_READ_WRITE, "film");
    for (int i = 0; i < 3000; ++i) {
        Buffer next = ctx.buffer(film, CL_MEM_READ_WRITE, "film");
        current = std::move(next);
    }
    EXPECT_EQ(ctx.allocated_bytes(), film);
    // The limit still holds for what is alive.
    Buffer second = ctx.buffer(film, CL_MEM_READ_WRITE, "second");
    try {
        Buffer third = ctx.buffer(film, CL_MEM_READ_WRITE, "third");
        FAIL() << "three buffers of two fifths of the limit fit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("global memory"), std::string::npos) << e.what();
    }
}

TEST(DeviceMemory, ABufferMayOutliveItsContext) {
    std::unique_ptr<Context> ctx = std::make_unique<Context>(test::device().device());
    Buffer b = ctx->buffer(1000, CL_MEM_READ_WRITE, "survivor");
    ctx.reset();
    // b is freed at the end of the test: its counter and cl_mem outlive the Context.
    EXPECT_EQ(b.bytes(), 1000u);
}
