// The SAH builder's partitions (host/bvh/partition.cpp): the portable and
// AVX versions put every record where a plain loop over BinMap::left_of
// puts it (front in order, back in reverse or in order) and grow the sides'
// centroid bounds bit for bit alike, and the stable scatter writes nothing
// outside its two ranges.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "bvh/partition.hpp"
#include "support/box_bits.hpp"

using namespace clpath::bvh_build;

namespace {

std::vector<Ref> random_refs(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.0f, 0.05f);
    std::vector<Ref> refs(n);
    for (std::size_t i = 0; i < n; ++i) {
        Ref& r = refs[i];
        for (int a = 0; a < 3; ++a) {
            const float c = u(rng);
            r.lo[a] = i % 9 == 0 ? ((i / 9) % 2 ? -0.0f : 0.0f) : c - s(rng);  // signed zeros meet in the bounds
            r.hi[a] = i % 9 == 0 ? r.lo[a] : c + s(rng);
        }
        r.prim = std::uint32_t(i);
        r.pad = float(i % 5);
    }
    return refs;
}

Box4 centroid_bounds(const std::vector<Ref>& refs, std::size_t begin, std::size_t end) {
    Box4 c;
    for (std::size_t i = begin; i < end; ++i) c.grow_point(centroid(load3(refs[i].lo), load3(refs[i].hi)));
    return c;
}

void expect_bitwise(const Box4& a, const Box4& b) { EXPECT_TRUE(clpath::test::same_box_bits(a, b)); }

// The reference: a branchy loop over BinMap::left_of.
struct Expected {
    std::vector<Ref> left, right;  // in source order
    Box4 lcb, rcb;
};
Expected reference(const std::vector<Ref>& refs, std::uint32_t begin, std::uint32_t end, const BinMap& map, int axis,
                   int bin) {
    Expected e;
    for (std::uint32_t i = begin; i < end; ++i) {
        const F4 c = centroid(load3(refs[i].lo), load3(refs[i].hi));
        if (map.left_of(c, axis, bin)) {
            e.left.push_back(refs[i]);
            e.lcb.grow_point(c);
        } else {
            e.right.push_back(refs[i]);
            e.rcb.grow_point(c);
        }
    }
    return e;
}

// n copies of fill, 64-byte aligned (so the streaming stores are taken).
struct FreeDeleter {
    void operator()(Ref* p) const { std::free(p); }
};
std::unique_ptr<Ref[], FreeDeleter> aligned_refs(std::size_t n, const Ref& fill) {
    Ref* p = static_cast<Ref*>(std::aligned_alloc(64, (n * sizeof(Ref) + 63) / 64 * 64));
    for (std::size_t i = 0; i < n; ++i) p[i] = fill;
    return std::unique_ptr<Ref[], FreeDeleter>(p);
}

bool same_ref(const Ref& a, const Ref& b) { return std::memcmp(&a, &b, sizeof(Ref)) == 0; }

using Engine = std::function<std::uint32_t(const Ref*, Ref*, std::uint32_t, std::uint32_t, std::uint32_t,
                                           std::uint32_t, std::uint32_t, const BinMap&, int, int, Box4&, Box4&)>;

void check_engine(const Engine& engine) {
    const std::vector<Ref> refs = random_refs(3000, 17);
    Ref sentinel{};
    sentinel.prim = 0xdeadbeefu;
    for (int bins : {2, 16, 64})
        for (std::uint32_t begin : {0u, 7u})
            for (std::uint32_t end : {begin + 1, begin + 2, begin + 33, std::uint32_t(refs.size())})
                for (int axis = 0; axis < 3; ++axis)
                    for (int bin : {0, bins / 2 - 1 < 0 ? 0 : bins / 2 - 1, bins - 2}) {
                        const BinMap map(centroid_bounds(refs, begin, end), bins);
                        const Expected e = reference(refs, begin, end, map, axis, bin);
                        const std::uint32_t nl = std::uint32_t(e.left.size());
                        // Reverse order at the back, as partition_refs.
                        const auto dst = aligned_refs(refs.size() + 2, sentinel);
                        Box4 lcb, rcb;
                        const std::uint32_t m = engine(refs.data(), dst.get() + 1, begin, end, begin, end - 1, ~0u,
                                                       map, axis, bin, lcb, rcb);
                        ASSERT_EQ(m, begin + nl);
                        for (std::uint32_t k = 0; k < nl; ++k) EXPECT_TRUE(same_ref(dst[1 + begin + k], e.left[k]));
                        for (std::size_t k = 0; k < e.right.size(); ++k)
                            EXPECT_TRUE(same_ref(dst[1 + end - 1 - k], e.right[k]));
                        EXPECT_TRUE(same_ref(dst[begin], sentinel));
                        EXPECT_TRUE(same_ref(dst[1 + end], sentinel));
                        if (nl) expect_bitwise(lcb, e.lcb);
                        if (!e.right.empty()) expect_bitwise(rcb, e.rcb);
                        // Stable, into two ranges apart with guards around each.
                        const std::uint32_t la = 1, ra = nl + 3;
                        const auto out = aligned_refs(nl + e.right.size() + 5, sentinel);
                        engine(refs.data(), out.get(), begin, end, la, ra, 1u, map, axis, bin, lcb, rcb);
                        for (std::uint32_t k = 0; k < nl; ++k) EXPECT_TRUE(same_ref(out[la + k], e.left[k]));
                        for (std::size_t k = 0; k < e.right.size(); ++k) EXPECT_TRUE(same_ref(out[ra + k], e.right[k]));
                        for (std::size_t k : {std::size_t(0), std::size_t(la + nl), std::size_t(la + nl + 1),
                                              ra + e.right.size(), ra + e.right.size() + 1})
                            EXPECT_TRUE(same_ref(out[k], sentinel)) << "guard " << k;
                        if (nl) expect_bitwise(lcb, e.lcb);
                        if (!e.right.empty()) expect_bitwise(rcb, e.rcb);
                    }
}

}  // namespace

TEST(Partition, PortableMatchesTheReference) { check_engine(partition_portable); }

// The AVX engine, with ordinary or streaming stores, through check_engine.
void check_avx(bool stream) {
    if (!avx_available()) GTEST_SKIP() << "no AVX on this CPU";
    check_engine([stream](const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end, std::uint32_t left_at,
                          std::uint32_t right_at, std::uint32_t step, const BinMap& map, int axis, int bin, Box4& lcb,
                          Box4& rcb) {
        return partition_avx(src, dst, begin, end, left_at, right_at, step, map, axis, bin, lcb, rcb, stream);
    });
}

TEST(Partition, AvxMatchesTheReference) { check_avx(false); }

TEST(Partition, AvxStreamingMatchesTheReference) { check_avx(true); }

TEST(Partition, DispatchedEntryPointsMatchTheEngines) {
    const std::vector<Ref> refs = random_refs(1000, 4);
    const BinMap map(centroid_bounds(refs, 0, refs.size()), 16);
    std::vector<Ref> a(refs.size()), b(refs.size());
    Box4 la, ra, lb, rb;
    const std::uint32_t ma = partition_refs(refs.data(), a.data(), 0, 1000, map, 1, 6, la, ra);
    const std::uint32_t mb = partition_portable(refs.data(), b.data(), 0, 1000, 0, 999, ~0u, map, 1, 6, lb, rb);
    EXPECT_EQ(ma, mb);
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(same_ref(a[k], b[k]));
    expect_bitwise(la, lb);
    expect_bitwise(ra, rb);
}
