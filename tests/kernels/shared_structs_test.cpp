// The structs of kernels/shared_structs.h have the same size on host and device.
#include <gtest/gtest.h>

#include "shared_structs.h"
#include "support/test_device.hpp"

using namespace clpath;

TEST(SharedStructs, SizesAgreeOnHostAndDevice) {
    Kernel k = test::device().kernel(test::probe_program(), "probe_struct_sizes");
    Buffer out = test::device().buffer(12 * sizeof(std::uint32_t), CL_MEM_READ_WRITE, "sizes");
    k.arg(0, out);
    test::run(k, 1);
    auto sizes = test::download<std::uint32_t>(out, 12);
    EXPECT_EQ(sizes[0], sizeof(BvhNode));
    EXPECT_EQ(sizes[1], sizeof(TriVerts));
    EXPECT_EQ(sizes[2], sizeof(Material));
    EXPECT_EQ(sizes[3], sizeof(CameraData));
    EXPECT_EQ(sizes[4], sizeof(FrameParams));
    EXPECT_EQ(sizes[5], sizeof(Counters));
    EXPECT_EQ(sizes[6], sizeof(AccumPixel));
    EXPECT_EQ(sizes[7], sizeof(Light));
    EXPECT_EQ(sizes[8], sizeof(AliasEntry));
    EXPECT_EQ(sizes[9], sizeof(BatchRay));
    EXPECT_EQ(sizes[10], sizeof(BatchHit));
    EXPECT_EQ(sizes[11], sizeof(Bvh4Node));
}
