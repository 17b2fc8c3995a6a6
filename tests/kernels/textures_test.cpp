// Texture lookups of kernels/textures.cl: texel layout, bilinear and nearest
// filtering, repeat / clamp / mirror addressing, sRGB decoding, float texels;
// against a double-precision reference written from the definitions (texel
// centres at half-integers, OpenGL's wrap rules).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "render/surface_buffers.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

Texture make_texture(int w, int h, bool is_float, std::uint32_t ws, std::uint32_t wt, bool nearest, std::uint32_t seed) {
    Texture t;
    t.width = w;
    t.height = h;
    t.is_float = is_float;
    t.wrap_s = ws;
    t.wrap_t = wt;
    t.nearest = nearest;
    std::mt19937 rng(seed);
    for (int i = 0; i < w * h * 4; ++i) {
        if (is_float) t.rgba32.push_back(std::uniform_real_distribution<float>(0, 8)(rng));
        else t.rgba8.push_back(std::uint8_t(rng() & 255));
    }
    return t;
}

double srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

int wrap(long i, int n, std::uint32_t mode) {
    if (mode == CLP_WRAP_CLAMP) return int(std::clamp<long>(i, 0, n - 1));
    if (mode == CLP_WRAP_MIRROR) {
        long p = ((i % (2 * n)) + 2 * n) % (2 * n);
        return int(p < n ? p : 2 * n - 1 - p);
    }
    return int(((i % n) + n) % n);
}

double texel(const Texture& t, int x, int y, int c, bool dec) {
    const std::size_t i = (std::size_t(y) * t.width + x) * 4 + c;
    if (t.is_float) return t.rgba32[i];
    const double v = t.rgba8[i] / 255.0;
    return dec && c < 3 ? srgb(v) : v;
}

// Texel coordinates (x, y) = (u w, v h): nearest takes the texel containing
// them, bilinear the four centres (x - 1/2, y - 1/2) lies between, wrapped.
double reference(const Texture& t, double u, double v, int c, bool dec) {
    double x = u * t.width, y = v * t.height;
    if (t.wrap_s == CLP_WRAP_CLAMP) x = std::clamp(u, 0.0, 1.0) * t.width;
    if (t.wrap_t == CLP_WRAP_CLAMP) y = std::clamp(v, 0.0, 1.0) * t.height;
    if (t.nearest) return texel(t, wrap(long(std::floor(x)), t.width, t.wrap_s), wrap(long(std::floor(y)), t.height, t.wrap_t), c, dec);
    x -= 0.5;
    y -= 0.5;
    const long x0 = long(std::floor(x)), y0 = long(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    auto at = [&](long xi, long yi) { return texel(t, wrap(xi, t.width, t.wrap_s), wrap(yi, t.height, t.wrap_t), c, dec); };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) + fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

std::vector<cl_float4> sample_device(const Scene& s, int index, bool dec, const std::vector<cl_float2>& uv) {
    const SurfaceBuffers b = pack_surface_buffers(s);
    Buffer desc = test::upload(b.textures), texels = test::upload(b.texels), uvb = test::upload(uv);
    Buffer out = test::device().buffer(uv.size() * sizeof(cl_float4), CL_MEM_READ_WRITE, "out");
    Kernel k = test::device().kernel(test::probe_program(), "probe_texture");
    k.arg(0, desc).arg(1, texels).arg(2, index).arg(3, int(dec)).arg(4, std::uint32_t(uv.size())).arg(5, uvb).arg(6, out);
    test::run(k, uv.size());
    return test::download<cl_float4>(out, uv.size());
}

}  // namespace

// Every wrap mode on each axis, both filters, 8-bit (linear and sRGB) and float
// texels, at random coordinates well outside [0, 1].
TEST(Textures, MatchReferenceForEveryModeAndFilter) {
    Scene s;
    std::uint32_t seed = 1;
    struct Use {
        int index;
        bool dec;
    };
    std::vector<Use> uses;
    for (std::uint32_t ws : {CLP_WRAP_REPEAT, CLP_WRAP_CLAMP, CLP_WRAP_MIRROR})
        for (std::uint32_t wt : {CLP_WRAP_REPEAT, CLP_WRAP_CLAMP, CLP_WRAP_MIRROR})
            for (bool nearest : {false, true})
                for (bool is_float : {false, true}) {
                    s.textures.push_back(make_texture(5, 3, is_float, ws, wt, nearest, seed++));
                    uses.push_back({int(s.textures.size() - 1), !is_float && (seed % 2 == 0)});
                }
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-3.0f, 4.0f);
    std::vector<cl_float2> uv;
    for (int i = 0; i < 400; ++i) uv.push_back(cl_float2{{u(rng), u(rng)}});
    // Texel centres and edges exactly, where filters switch texels.
    uv.push_back(cl_float2{{0.1f, 1.0f / 6}});
    uv.push_back(cl_float2{{0.0f, 0.0f}});
    uv.push_back(cl_float2{{1.0f, 1.0f}});
    for (const Use& use : uses) {
        const Texture& t = s.textures[std::size_t(use.index)];
        const auto got = sample_device(s, use.index, use.dec, uv);
        for (std::size_t i = 0; i < uv.size(); ++i)
            for (int c = 0; c < 4; ++c) {
                const double want = reference(t, uv[i].s[0], uv[i].s[1], c, use.dec);
                // Float rounding of the coordinate (|u| <= 4, 2^-22 relative) moves
                // the weights by ~1e-5 of a texel; values are below 8.
                EXPECT_NEAR(got[i].s[c], want, 2e-4 * (1 + std::abs(want)))
                    << "texture " << use.index << " uv (" << uv[i].s[0] << ", " << uv[i].s[1] << ") channel " << c;
            }
    }
}

// Known values: a 2x1 RGBA8 texture, red then grey 128 (sRGB 0.2158605 linear).
TEST(Textures, KnownTexelsAndSrgb) {
    Scene s;
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 0, 0, 255, 128, 128, 128, 0};
    t.wrap_s = CLP_WRAP_REPEAT;
    s.textures.push_back(t);
    const std::vector<cl_float2> uv = {{{0.25f, 0.5f}}, {{0.75f, 0.5f}}, {{0.5f, 0.5f}}, {{1.25f, 0.5f}}};
    const auto lin = sample_device(s, 0, false, uv), dec = sample_device(s, 0, true, uv);
    EXPECT_FLOAT_EQ(lin[0].s[0], 1.0f);
    EXPECT_FLOAT_EQ(lin[1].s[1], 128 / 255.0f);
    EXPECT_FLOAT_EQ(lin[1].s[3], 0.0f);
    EXPECT_NEAR(dec[1].s[1], 0.2158605f, 1e-6f);
    EXPECT_NEAR(lin[2].s[3], 0.5f, 1e-6f);  // halfway between the centres: the mean
    EXPECT_FLOAT_EQ(lin[3].s[0], lin[0].s[0]);  // repeat
}
