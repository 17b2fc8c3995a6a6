// The cache keys' and checkpoints' hash (cl/program.hpp): FNV-1a's step, whose
// values a checkpoint stores, so they must not change.
#include <gtest/gtest.h>

#include <string>

#include "cl/program.hpp"

namespace clpath {
namespace {

TEST(Fnv1a64, PublishedValuesFromThePublishedBasis) {
    // FNV-1a 64-bit test vectors (Fowler, Noll and Vo; IETF draft-eastlake-fnv),
    // from the published offset basis; clpath's default seed is another value.
    const std::uint64_t basis = 14695981039346656037ull;
    EXPECT_EQ(fnv1a64(std::string(), basis), 0xcbf29ce484222325ull);
    EXPECT_EQ(fnv1a64(std::string("a"), basis), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(fnv1a64(std::string("foobar"), basis), 0x85944171f73967e8ull);
    const std::string foobar = "foobar";
    EXPECT_EQ(fnv1a64(foobar.data(), foobar.size(), basis), 0x85944171f73967e8ull);
}

TEST(Fnv1a64, DefaultSeedKeepsTheValuesCheckpointsHold) {
    // The default seed is 1469598103934665603, the published basis short of its
    // last digit (so not FNV-1a's values); kept, since checkpoints written by
    // earlier builds store hashes made with it (render/render_hash.cpp).
    EXPECT_EQ(kFnv1a64Seed, 1469598103934665603ull);
    EXPECT_EQ(fnv1a64(std::string()), 1469598103934665603ull);
    EXPECT_EQ(fnv1a64(std::string("foobar")), 9870438755804841970ull);
}

TEST(Fnv1a64, BytesInPlaceHashAsTheirText) {
    const std::string text("clpath\0scene bytes", 18), other("clpath\0scene bytez", 18);  // NUL inside
    for (std::uint64_t seed : {kFnv1a64Seed, std::uint64_t(42)}) {
        EXPECT_EQ(fnv1a64(text.data(), text.size(), seed), fnv1a64(text, seed));
        EXPECT_NE(fnv1a64(other.data(), other.size(), seed), fnv1a64(text, seed));  // control: one byte differs
    }
}

}  // namespace
}  // namespace clpath
