// length3 and normalize3 (kernels/common.h) for vectors of every magnitude a
// float holds: where the squared length over- or underflows, the builtins'
// results bit for bit (they are what answers there); elsewhere within the
// float error of sqrt(dot(v, v)) of the exact length (on PoCL, whose builtins
// compute that formula there, the same bits as the builtins too).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "support/test_device.hpp"

namespace clpath {
namespace {

struct LengthResults {
    std::vector<float> len, len_builtin, unit, unit_builtin, unguarded;
};

LengthResults run_length3(const std::vector<float>& v) {
    const auto n = static_cast<std::uint32_t>(v.size() / 3);
    Kernel k = test::device().kernel(test::probe_program(), "probe_length3");
    Buffer in = test::upload(v);
    auto out = [&](std::size_t floats) {
        return test::device().buffer(floats * sizeof(float), CL_MEM_READ_WRITE, "lengths");
    };
    Buffer len = out(n), len_b = out(n), unit = out(3 * n), unit_b = out(3 * n), ung = out(n);
    k.arg(0, in).arg(1, len).arg(2, len_b).arg(3, unit).arg(4, unit_b).arg(5, ung).arg(6, n);
    test::run(k, n);
    return {test::download<float>(len, n), test::download<float>(len_b, n), test::download<float>(unit, 3 * n),
            test::download<float>(unit_b, 3 * n), test::download<float>(ung, n)};
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Vectors with components of magnitude 2^e for e across the float range
// (from subnormal to near the largest), random signs and mantissas.
std::vector<float> vectors_of_every_scale() {
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> mant(1.0f, 2.0f);
    std::vector<float> v;
    for (int e = -140; e <= 126; ++e)
        for (int k = 0; k < 16; ++k)
            for (int c = 0; c < 3; ++c) {
                const float sign = (gen() & 1) ? -1.0f : 1.0f;
                v.push_back(sign * std::ldexp(mant(gen), e + int(gen() % 3) - 1));
            }
    return v;
}

TEST(Length3, RightAtEveryScale) {
    const std::vector<float> v = vectors_of_every_scale();
    const LengthResults r = run_length3(v);
    // In the fast path, u = 2^-24: the dot's three roundings (3u), halved by
    // the square root, and the square root's own 3 ulp (6u) that OpenCL
    // allows: 7.5u of the exact length; normalize's rsqrt (2 ulp, 4u), the
    // dot (1.5u) and the product (u): 6.5u of 1 in each component. Bound: 8u.
    const double bound = 8.0 * std::ldexp(1.0, -24);
    std::size_t fallback = 0;
    for (std::size_t i = 0; i < r.len.size(); ++i) {
        const double x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
        const float d = float(x) * float(x) + float(y) * float(y) + float(z) * float(z);
        const double exact = std::sqrt(x * x + y * y + z * z);
        if (!(std::isnormal(d) && std::isfinite(d))) {
            ++fallback;
            ASSERT_TRUE(same_bits(r.len[i], r.len_builtin[i])) << "vector " << i;
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(same_bits(r.unit[3 * i + c], r.unit_builtin[3 * i + c])) << i;
            continue;
        }
        ASSERT_LE(std::fabs(r.len[i] - exact), bound * exact) << "vector " << i;
        const double comp[3] = {x, y, z};
        for (int c = 0; c < 3; ++c) ASSERT_LE(std::fabs(r.unit[3 * i + c] - comp[c] / exact), bound) << i;
    }
    EXPECT_GT(fallback, r.len.size() / 4);  // both paths were checked, each for over a quarter of the vectors
    EXPECT_LT(fallback, r.len.size() * 3 / 4);
}

// Control: where the squared length over- or underflows, sqrt(dot(v, v))
// alone is wrong (0, subnormal-inexact or infinite), so the check above
// exercised the fallback and not only the fast path.
TEST(Length3, ControlTheUnguardedFormulaFailsAtTheExtremes) {
    const LengthResults r = run_length3({1e-30f, 2e-30f, -2e-30f, 3e25f, -4e25f, 0.0f, 0.6f, 0.8f, 0.0f});
    EXPECT_FALSE(same_bits(r.unguarded[0], r.len_builtin[0]));  // underflow
    EXPECT_NEAR(r.len[0], 3e-30f, 3e-30f * 1e-6f);
    EXPECT_FALSE(same_bits(r.unguarded[1], r.len_builtin[1]));  // overflow
    EXPECT_NEAR(r.len[1], 5e25f, 5e25f * 1e-6f);
    EXPECT_TRUE(same_bits(r.unguarded[2], r.len_builtin[2]));   // the common case: the same formula
    EXPECT_EQ(r.len[2], 1.0f);
}

}  // namespace
}  // namespace clpath
