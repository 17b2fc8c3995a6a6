// The OpenCL runtime layer (host/cl/): errors by name, build logs, the
// binary cache, size checks before allocation.
#include <gtest/gtest.h>

#include <filesystem>

#include "cl/embedded_sources.hpp"
#include "cl/errors.hpp"
#include "support/test_device.hpp"
#include "util/error.hpp"

using namespace clpath;

TEST(ClRuntime, ErrorsAreNamed) {
    EXPECT_STREQ(cl_error_name(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES");
    EXPECT_STREQ(cl_error_name(CL_BUILD_PROGRAM_FAILURE), "CL_BUILD_PROGRAM_FAILURE");
    try {
        cl_check(CL_INVALID_KERNEL_NAME, "making a kernel");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "making a kernel: CL_INVALID_KERNEL_NAME (-46)");
    }
}

TEST(ClRuntime, BuildFailureReportsTheLog) {
    const std::string bad = "kernel void broken(global float* x) { x[0] = undefined_name; }\n";
    try {
        build_program(test::device(), bad, "-cl-std=CL1.2");
        FAIL() << "a broken kernel built";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("kernel build failed"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undefined_name"), std::string::npos) << "the build log should name the error: " << msg;
    }
}

TEST(ClRuntime, CachedBinaryIsUsedTheSecondTime) {
    const auto dir = std::filesystem::temp_directory_path() / ("clpath-cache-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    ::setenv("CLPATH_CACHE_DIR", dir.c_str(), 1);
    const std::string src = "kernel void k(global int* x) { x[get_global_id(0)] = 7; }\n";
    auto first = build_program(test::device(), src, "-cl-std=CL1.2");
    auto second = build_program(test::device(), src, "-cl-std=CL1.2");
    auto other = build_program(test::device(), src, "-cl-std=CL1.2 -DX=1");
    EXPECT_FALSE(first.from_cache);
    EXPECT_TRUE(second.from_cache);
    EXPECT_FALSE(other.from_cache) << "other options must not reuse the binary";
    // The cached program works.
    Kernel k = test::device().kernel(second.program.get(), "k");
    Buffer b = test::device().buffer(4 * sizeof(int), CL_MEM_READ_WRITE, "x");
    k.arg(0, b);
    test::run(k, 4);
    EXPECT_EQ(test::download<int>(b, 4), std::vector<int>(4, 7));
    // A corrupt cache file is rebuilt, not trusted.
    for (const auto& f : std::filesystem::directory_iterator(dir)) std::filesystem::resize_file(f.path(), 10);
    auto again = build_program(test::device(), src, "-cl-std=CL1.2");
    EXPECT_FALSE(again.from_cache);
    std::filesystem::remove_all(dir);
}

TEST(ClRuntime, TooLargeAllocationIsAClearError) {
    const auto& d = test::device().device();
    try {
        test::device().buffer(std::size_t(d.max_alloc) + 1, CL_MEM_READ_WRITE, "a giant test buffer");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("a giant test buffer"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("CL_DEVICE_MAX_MEM_ALLOC_SIZE"), std::string::npos) << e.what();
    }
    try {
        // Each buffer within the single-allocation limit, together more than the device has.
        std::vector<std::pair<std::string, std::size_t>> many(d.global_mem / d.max_alloc + 1,
                                                              {"a part", std::size_t(d.max_alloc)});
        test::device().check_fits(many);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("global memory"), std::string::npos) << e.what();
    }
}

TEST(ClRuntime, KernelSourcesAreEmbedded) {
    for (const auto& f : renderer_kernel_files()) EXPECT_FALSE(embedded_source(f).empty()) << f;
    EXPECT_THROW(embedded_source("no_such.cl"), Error);
}
