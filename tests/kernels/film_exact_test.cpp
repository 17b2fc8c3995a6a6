// film_add_exact (kernels/film.cl), the device's half of the exact film: a
// chunk's compensated float sums turned into 128-bit fixed point and added to
// the running image must give, bit for bit, what the host's ExactFilm gives
// (render/exact_film.hpp), for floats of every exponent and sign, with zero
// compensations (a one-sample chunk) and without; and a pixel holding a value
// the fixed point cannot hold is left alone and reported.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "render/exact_film.hpp"
#include "shared_structs.h"
#include "support/test_device.hpp"

namespace clpath {
namespace {

using U128 = unsigned __int128;

struct Exact128 {  // as the kernel stores it: a ulong2, low half first
    std::uint64_t lo, hi;
};
static_assert(sizeof(Exact128) == 16);

U128 as_u128(Exact128 e) { return (U128(e.hi) << 64) | e.lo; }
Exact128 from_u128(U128 v) { return {std::uint64_t(v), std::uint64_t(v >> 64)}; }

struct AddResult {
    std::vector<AccumPixel> accum;
    std::vector<Exact128> exact;
    std::uint32_t error = 0;
};

AddResult run_add_exact(const std::vector<AccumPixel>& accum, const std::vector<Exact128>& exact) {
    const auto n = std::uint32_t(accum.size());
    Kernel k = test::device().kernel(test::probe_program(), "film_add_exact");
    Buffer a = test::upload(accum, "chunk film"), e = test::upload(exact, "exact film");
    Buffer err = test::upload(std::vector<std::uint32_t>{0}, "error");
    k.arg(0, a).arg(1, n).arg(2, e).arg(3, err);
    test::run(k, n);
    return {test::download<AccumPixel>(a, n), test::download<Exact128>(e, 3 * std::size_t(n)),
            test::download<std::uint32_t>(err, 1)[0]};
}

// Finite floats of magnitude below 2^63, every biased exponent from 0
// (subnormals) to 189 with random mantissas and signs, zeros of both signs,
// and the extremes of the exact range.
float finite_in_range(std::mt19937& rng) {
    std::uniform_int_distribution<std::uint32_t> exponent(0, 189), mantissa(0, 0x7fffff), sign(0, 1), kind(0, 15);
    switch (kind(rng)) {
        case 0: return sign(rng) ? -0.0f : 0.0f;
        case 1: return std::bit_cast<float>((sign(rng) << 31) | (189u << 23) | 0x7fffffu);  // just below 2^63
        case 2: return std::bit_cast<float>((sign(rng) << 31) | 1u);                         // the smallest subnormal
        default: return std::bit_cast<float>((sign(rng) << 31) | (exponent(rng) << 23) | mantissa(rng));
    }
}

std::vector<Exact128> random_exact(std::mt19937_64& rng, std::size_t n) {
    std::vector<Exact128> v(n);
    for (auto& e : v) e = {rng(), rng()};
    return v;
}

// The first channel where after is not before plus what the host adds for
// the pixel (sum - comp in fixed point), or -1 where all three agree.
int channel_off_the_host(const AccumPixel& p, const Exact128* before, const Exact128* after) {
    for (int c = 0; c < 3; ++c)
        if (as_u128(after[c]) != as_u128(before[c]) + U128(to_fixed(p.sum[c])) - U128(to_fixed(p.comp[c]))) return c;
    return -1;
}

TEST(FilmAddExact, MatchesTheHostForEveryExponentWithAndWithoutCompensation) {
    std::mt19937 rng(7);
    std::mt19937_64 rng64(11);
    const std::size_t n = 20000;
    std::vector<AccumPixel> accum(n);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c) {
            accum[i].sum[c] = finite_in_range(rng);
            // Half the pixels as a one-sample chunk leaves them: no compensation.
            accum[i].comp[c] = i % 2 ? finite_in_range(rng) : 0.0f;
        }
    const std::vector<Exact128> before = random_exact(rng64, 3 * n);
    const AddResult r = run_add_exact(accum, before);
    EXPECT_EQ(r.error, 0u);
    for (std::size_t i = 0; i < n; ++i) {
        const int c = channel_off_the_host(accum[i], &before[3 * i], &r.exact[3 * i]);
        ASSERT_EQ(c, -1) << "pixel " << i << ": sum " << accum[i].sum[c < 0 ? 0 : c] << " comp "
                         << accum[i].comp[c < 0 ? 0 : c];
        for (int c = 0; c < 4; ++c) ASSERT_EQ(r.accum[i].sum[c], 0.0f) << "the chunk film is emptied";
        for (int c = 0; c < 4; ++c) ASSERT_EQ(r.accum[i].comp[c], 0.0f) << "the chunk film is emptied";
    }
}

TEST(FilmAddExact, AValueItCannotHoldLeavesThePixelAndIsReported) {
    // Pixel 0 and 2 ordinary; pixel 1 has one bad value, in the sum or the compensation.
    struct Case {
        float value;
        bool in_comp;
        std::uint32_t bit;
    };
    const float inf = std::numeric_limits<float>::infinity();
    const Case cases[] = {{inf, false, 1u},
                          {-inf, true, 1u},
                          {std::numeric_limits<float>::quiet_NaN(), true, 1u},
                          {0x1p63f, false, 2u},
                          {-0x1p70f, true, 2u},
                          {std::numeric_limits<float>::max(), false, 2u}};
    std::mt19937_64 rng64(3);
    for (const Case& k : cases) {
        std::vector<AccumPixel> accum(3);
        for (auto& p : accum)
            for (int c = 0; c < 4; ++c) p.sum[c] = 0.25f * float(c + 1), p.comp[c] = 0.0f;
        (k.in_comp ? accum[1].comp : accum[1].sum)[1] = k.value;
        const std::vector<Exact128> before = random_exact(rng64, 9);
        const AddResult r = run_add_exact(accum, before);
        EXPECT_EQ(r.error, k.bit) << k.value;
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(as_u128(r.exact[3 + c]) == as_u128(before[3 + c])) << k.value;
        EXPECT_EQ(std::memcmp(&r.accum[1], &accum[1], sizeof(AccumPixel)), 0) << "a refused pixel keeps its chunk";
        EXPECT_EQ(channel_off_the_host(accum[0], &before[0], &r.exact[0]), -1) << k.value;
        EXPECT_EQ(channel_off_the_host(accum[2], &before[6], &r.exact[6]), -1) << k.value;
    }
}

// Control: the comparison sees a one-unit difference (2^-64) in any channel.
TEST(FilmAddExact, ControlALastUnitOffIsSeen) {
    AccumPixel p{};
    for (int c = 0; c < 4; ++c) p.sum[c] = 1.5f;
    const std::vector<Exact128> before(3, Exact128{0, 0});
    const AddResult r = run_add_exact({p}, before);
    ASSERT_EQ(r.error, 0u);
    std::vector<Exact128> off = r.exact;
    off[2] = from_u128(as_u128(off[2]) + 1);
    EXPECT_EQ(channel_off_the_host(p, before.data(), r.exact.data()), -1);
    EXPECT_EQ(channel_off_the_host(p, before.data(), off.data()), 2);
}

}  // namespace
}  // namespace clpath
