// kernels/light_bvh.cl on the device against its host reference
// (host/render/light_bvh.*): the device's pick reports the pmf its own trail
// walk gives, and picks and pmfs agree with the host's up to float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "render/light_bvh.hpp"
#include "support/test_device.hpp"

namespace clpath {
namespace {

glm::vec3 unit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

std::vector<Light> lights(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<Light> v;
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 c = glm::vec3(u(rng), u(rng), u(rng)) * 10.0f - 5.0f;
        const float s = 0.05f + 0.3f * u(rng);
        Light l{};
        l.type = i % 10 == 0 ? CLP_LIGHT_SPOT : i % 10 == 1 ? CLP_LIGHT_POINT : CLP_LIGHT_TRIANGLE;
        store3(l.a, c + s * unit(rng));
        store3(l.b, l.type == CLP_LIGHT_SPOT ? unit(rng) : c + s * unit(rng));
        store3(l.c, c + s * unit(rng));
        store3(l.L, glm::vec3(u(rng), u(rng), u(rng)) * (i % 13 == 0 ? 50.0f : 1.0f));
        l.flags = i % 4 == 0 ? CLP_LIGHTF_TWO_SIDED : 0u;
        l.cos_inner = std::cos(0.4f);
        l.cos_outer = std::cos(0.7f);
        v.push_back(l);
    }
    Light e{};
    e.type = CLP_LIGHT_ENVIRONMENT;
    v.push_back(e);
    return v;
}

TEST(LightBvhKernel, PicksAndPmfsMatchTheHostReference) {
    std::mt19937 rng(7);
    const auto ls = lights(rng);
    const LightBvh bvh = build_light_bvh(ls);
    const std::uint32_t n = 20000;
    std::vector<cl_float4> pn(n), nn(n);
    std::uniform_real_distribution<float> u(0, 1), x(-7, 7);
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::vec3 nv = i % 8 == 0 ? glm::vec3(0) : unit(rng);
        pn[i] = {{x(rng), x(rng), x(rng), u(rng)}};
        nn[i] = {{nv.x, nv.y, nv.z, 0.0f}};
    }
    std::vector<cl_uint2> trail(bvh.trail.size());
    for (std::size_t i = 0; i < trail.size(); ++i)
        trail[i] = {{std::uint32_t(bvh.trail[i]), std::uint32_t(bvh.trail[i] >> 32)}};
    Buffer nodes = test::upload(bvh.nodes, "nodes"), tb = test::upload(trail, "trails");
    Buffer inf = test::upload(bvh.infinite, "infinite"), pb = test::upload(pn, "points"), nb = test::upload(nn, "normals");
    Buffer out = test::device().buffer(n * sizeof(cl_float4), CL_MEM_READ_WRITE, "picks");
    Kernel k = test::device().kernel(test::probe_program(), "probe_light_bvh");
    const cl_float4 origin{{bvh.origin.x, bvh.origin.y, bvh.origin.z, 0}}, scale{{bvh.scale.x, bvh.scale.y, bvh.scale.z, 0}};
    k.arg(0, nodes).arg(1, tb).arg(2, inf).arg(3, origin).arg(4, scale).arg(5, std::uint32_t(bvh.nodes.size()));
    k.arg(6, std::uint32_t(bvh.infinite.size())).arg(7, n).arg(8, pb).arg(9, nb).arg(10, out);
    test::run(k, n);
    const auto got = test::download<cl_float4>(out, n);
    // Each importance is some 40 float operations (device sqrt and normalize
    // within a few ulp of the host's): 1e-5 relative per quotient, bounding a
    // pmf's product over depth + 1 levels.
    const double rel = 1e-5 * (bvh.depth + 1);
    int disagree = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        std::uint32_t li;
        std::memcpy(&li, &got[i].s[0], 4);
        ASSERT_EQ(got[i].s[1], got[i].s[2]) << "item " << i << ": the sampler's pmf is not its trail walk's";
        const glm::vec3 p(pn[i].s[0], pn[i].s[1], pn[i].s[2]), nv(nn[i].s[0], nn[i].s[1], nn[i].s[2]);
        const auto h = sample_light_bvh(bvh, p, nv, pn[i].s[3]);
        const std::uint32_t hl = h ? h->light : CLP_NO_LIGHT;
        if (hl != li) {
            ++disagree;  // u within rounding of a boundary between two children
            continue;
        }
        if (h) EXPECT_NEAR(got[i].s[1], h->pmf, rel * h->pmf) << "item " << i;
    }
    // u falls within rel of one of depth + 1 boundaries.
    EXPECT_LE(disagree, int(10 + 4 * n * rel)) << disagree << " of " << n << " picks differ";
}

}  // namespace
}  // namespace clpath
