// Every test probe kernel launched once on a few work-items with valid
// input, for the Oclgrind checks (tests/kernels/oclgrind_tests.cmake): the
// simulator then reports any out-of-bounds or uninitialised access or data
// race in the kernel code the probes call. The answers are checked by the
// *_test programs; here only that each launch completes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bvh/accel.hpp"
#include "kernels/shared_struct_fields.h"
#include "render/environment_map.hpp"
#include "render/light_bvh.hpp"
#include "robustness/robustness_probes.hpp"
#include "scene/scene.hpp"
#include "scene/shapes.hpp"
#include "support/test_device.hpp"
#include "support/traversal_probes.hpp"

using namespace clpath;

namespace {

constexpr std::uint32_t kN = 8;  // work-items per launch

template <class T>
Buffer out_buffer(std::size_t n) {
    return test::device().buffer(n * sizeof(T), CL_MEM_READ_WRITE, "probe output");
}

// Rays (origin, direction) from around a unit box towards its middle.
std::vector<float> rays_at_box() {
    std::vector<float> r;
    for (std::uint32_t i = 0; i < kN; ++i) {
        const float a = 0.7f * float(i);
        const glm::vec3 o(2.0f * std::cos(a), 0.3f * float(i) - 1.0f, 2.0f * std::sin(a));
        const glm::vec3 d = glm::normalize(glm::vec3(0.1f) - o);
        r.insert(r.end(), {o.x, o.y, o.z, d.x, d.y, d.z});
    }
    return r;
}

}  // namespace

TEST(ProbeKernels, Layout) {
    std::size_t n = 0;
#define COUNT_STRUCT(S) n += 1;
#define COUNT_FIELD(S, f) n += 2;
    CLP_SHARED_STRUCTS(COUNT_STRUCT)
    CLP_SHARED_FIELDS(COUNT_FIELD)
    Kernel k = test::device().kernel(test::probe_program(), "probe_struct_layout");
    Buffer out = out_buffer<std::uint32_t>(n);
    k.arg(0, out);
    test::run(k, 1);
    Kernel c = test::device().kernel(test::probe_program(), "probe_contracts");
    Buffer ints = out_buffer<std::uint32_t>(8), floats = out_buffer<float>(5);
    c.arg(0, ints).arg(1, floats);
    test::run(c, 1);
}

TEST(ProbeKernels, Environment) {
    for (bool sampled : {true, false}) {
        Environment e;
        e.image = CLPATH_TEST_KERNEL_DATA "/oclgrind-sky.pfm";
        e.importance_sampled = sampled;
        const EnvironmentMap m = load_environment_map(e);
        FrameParams fp{};
        fp.env_width = std::uint32_t(m.width);
        fp.env_height = std::uint32_t(m.height);
        fp.env_scale = 1;
        fp.env_rot_cos = std::cos(0.5f);
        fp.env_rot_sin = std::sin(0.5f);
        Buffer params = test::device().buffer(sizeof fp, CL_MEM_READ_ONLY, "frame parameters", &fp);
        Buffer pixels = test::upload(m.pixels), cdf = test::upload(m.cdf), out = out_buffer<cl_float4>(kN);
        Kernel k = test::device().kernel(test::probe_program(), "probe_env_sample");
        k.arg(0, params).arg(1, pixels).arg(2, cdf).arg(3, kN).arg(4, 1u).arg(5, out);
        test::run(k, kN);
    }
}

TEST(ProbeKernels, RandomNumbersAndDirections) {
    Kernel stream = test::device().kernel(test::probe_program(), "probe_rng_stream");
    Buffer s = out_buffer<float>(kN * 4);
    stream.arg(0, s).arg(1, kN).arg(2, 4u).arg(3, 1u).arg(4, 2u);
    test::run(stream, kN);
    Kernel first = test::device().kernel(test::probe_program(), "probe_rng_first");
    Buffer f = out_buffer<float>(kN);
    first.arg(0, f).arg(1, 4u).arg(2, 2u).arg(3, 3u);
    test::run(first, kN);
    Kernel cosine = test::device().kernel(test::probe_program(), "probe_cosine");
    Buffer c = out_buffer<float>(3 * kN);
    cosine.arg(0, c).arg(1, kN).arg(2, 4u);
    test::run(cosine, kN);
    std::vector<float> normals;
    for (std::uint32_t i = 0; i < kN; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(float(i) - 3.5f, 1.0f, i % 2 ? -1.0f : 1.0f));
        normals.insert(normals.end(), {n.x, n.y, n.z});
    }
    Kernel about = test::device().kernel(test::probe_program(), "probe_cosine_about");
    Buffer nb = test::upload(normals), a = out_buffer<float>(3 * kN);
    about.arg(0, nb).arg(1, a).arg(2, kN).arg(3, 5u);
    test::run(about, kN);
}

TEST(ProbeKernels, Intersection) {
    const std::vector<float> rays = rays_at_box();
    std::vector<float> tris;
    for (std::uint32_t i = 0; i < kN; ++i)
        tris.insert(tris.end(), {-1, -1, 0, 1, -1, 0, 0, 1, float(i) * 0.1f});
    Kernel k = test::device().kernel(test::probe_program(), "probe_triangle");
    Buffer rb = test::upload(rays), tb = test::upload(tris), out = out_buffer<float>(4 * kN);
    k.arg(0, rb).arg(1, tb).arg(2, out).arg(3, kN);
    test::run(k, kN);
}

TEST(ProbeKernels, Traversal) {
    const std::vector<glm::vec3> box = make_box();
    const Bvh bvh = build_bvh(box);
    const std::vector<float> rays = rays_at_box();
    const test::Traced through = test::trace_bvh(bvh, rays, std::vector<float>(kN, INFINITY));
    const test::Traced brute = test::trace_brute(test::device_triangles(box), rays);
    EXPECT_EQ(through.prim.size(), std::size_t(kN));
    EXPECT_EQ(brute.prim.size(), std::size_t(kN));
}

TEST(ProbeKernels, Materials) {
    const std::vector<Material> materials = {diffuse(glm::vec3(0.5f)), mirror(), conductor(glm::vec3(0.9f), 0.3f),
                                             conductor(glm::vec3(0.9f), 0.0f), dielectric(1.5f),
                                             dielectric(1.4f, 0.4f)};
    std::vector<cl_float4> wo(kN), wi(kN);
    for (std::uint32_t i = 0; i < kN; ++i) {
        const glm::vec3 a = glm::normalize(glm::vec3(0.3f * float(i) - 1.0f, 0.2f, i % 3 ? 1.0f : -1.0f));
        const glm::vec3 b = glm::normalize(glm::vec3(-0.5f, 0.1f * float(i), i % 2 ? 1.0f : -0.5f));
        wo[i] = {{a.x, a.y, a.z, 0}};
        wi[i] = {{b.x, b.y, b.z, 0}};
    }
    Buffer wob = test::upload(wo), wib = test::upload(wi);
    for (const Material& mat : materials) {
        Buffer m = test::upload(std::vector<Material>{mat});
        Kernel s = test::device().kernel(test::probe_program(), "probe_bsdf_sample");
        Buffer wi_pdf = out_buffer<cl_float4>(kN), weight = out_buffer<cl_float4>(kN);
        s.arg(0, m).arg(1, 0.3f).arg(2, -0.2f).arg(3, 0.93f).arg(4, kN).arg(5, 6u).arg(6, wi_pdf).arg(7, weight);
        test::run(s, kN);
        Kernel e = test::device().kernel(test::probe_program(), "probe_bsdf_eval");
        Buffer out = out_buffer<cl_float4>(kN);
        e.arg(0, m).arg(1, kN).arg(2, wob).arg(3, wib).arg(4, out);
        test::run(e, kN);
    }
}

TEST(ProbeKernels, TriangleLight) {
    Light l{};
    const float a[3] = {-0.5f, 1, -0.5f}, b[3] = {0.5f, 1, -0.5f}, c[3] = {0, 1, 0.5f};
    for (int i = 0; i < 3; ++i) {
        l.a[i] = a[i];
        l.b[i] = b[i];
        l.c[i] = c[i];
        l.L[i] = 1;
    }
    l.type = CLP_LIGHT_TRIANGLE;
    Buffer lb = test::upload(std::vector<Light>{l});
    // Near (solid-angle sampling), far (area sampling) and in the plane.
    for (glm::vec3 p : {glm::vec3(0, 0.5f, 0), glm::vec3(30, -40, 10), glm::vec3(2, 1, 0)}) {
        Kernel k = test::device().kernel(test::probe_program(), "probe_triangle_light");
        Buffer out = out_buffer<cl_float4>(kN), pdf = out_buffer<float>(kN);
        k.arg(0, lb).arg(1, p.x).arg(2, p.y).arg(3, p.z).arg(4, kN).arg(5, 7u).arg(6, out).arg(7, pdf);
        test::run(k, kN);
    }
}

TEST(ProbeKernels, LightBvh) {
    // Two triangles, a point light and the environment: a three-leaf tree.
    std::vector<Light> lights(4, Light{});
    for (int t = 0; t < 2; ++t) {
        const float x = 2.0f * float(t);
        const float a[3] = {x, 1, 0}, b[3] = {x + 1, 1, 0}, c[3] = {x, 1, 1};
        for (int i = 0; i < 3; ++i) {
            lights[t].a[i] = a[i];
            lights[t].b[i] = b[i];
            lights[t].c[i] = c[i];
            lights[t].L[i] = 1;
        }
        lights[t].type = CLP_LIGHT_TRIANGLE;
    }
    lights[2].type = CLP_LIGHT_POINT;
    lights[2].L[0] = lights[2].L[1] = lights[2].L[2] = 1;
    lights[3].type = CLP_LIGHT_ENVIRONMENT;
    const LightBvh bvh = build_light_bvh(lights);
    std::vector<cl_uint2> trail;
    for (std::uint64_t t : bvh.trail) trail.push_back({{std::uint32_t(t), std::uint32_t(t >> 32)}});
    std::vector<cl_float4> pn, nn;
    for (std::uint32_t i = 0; i < kN; ++i) {
        pn.push_back({{0.3f * float(i), 0.0f, 0.5f, (float(i) + 0.5f) / float(kN)}});
        nn.push_back({{0.0f, i % 2 ? 1.0f : 0.0f, 0.0f, 0.0f}});
    }
    Buffer nodes = test::upload(bvh.nodes), tb = test::upload(trail), inf = test::upload(bvh.infinite);
    Buffer pb = test::upload(pn), nb = test::upload(nn), out = out_buffer<cl_float4>(kN);
    const cl_float4 origin{{bvh.origin.x, bvh.origin.y, bvh.origin.z, 0}}, scale{{bvh.scale.x, bvh.scale.y, bvh.scale.z, 0}};
    Kernel k = test::device().kernel(test::probe_program(), "probe_light_bvh");
    k.arg(0, nodes).arg(1, tb).arg(2, inf).arg(3, origin).arg(4, scale).arg(5, std::uint32_t(bvh.nodes.size()));
    k.arg(6, std::uint32_t(bvh.infinite.size())).arg(7, kN).arg(8, pb).arg(9, nb).arg(10, out);
    test::run(k, kN);
}

TEST(ProbeKernels, Watertight) {
    const std::vector<glm::vec3> box = make_box();
    const Bvh bvh = build_bvh(box);
    std::vector<float> targets;
    for (std::size_t i = 0; i < 4; ++i) targets.insert(targets.end(), {box[i].x, box[i].y, box[i].z});
    Kernel k = test::device().kernel(test::robustness_program(), "probe_watertight");
    Buffer nodes = test::upload(device_nodes(Accel::Bvh, bvh, test::node_layout())), tris = test::upload(bvh.triangles), tb = test::upload(targets);
    Buffer leaks = test::upload(std::vector<std::uint32_t>{0});
    Buffer first = test::upload(std::vector<std::uint64_t>{0});
    k.arg(0, nodes).arg(1, tris).arg(2, tb).arg(3, 4u).arg(4, 0.0f).arg(5, 0.0f).arg(6, 0.0f);
    k.arg(7, 0.2f).arg(8, 0.05f).arg(9, cl_ulong(0)).arg(10, 4 * kN).arg(11, 1u).arg(12, leaks).arg(13, first);
    test::run(k, 4 * kN);
}

// The controls, run only under Oclgrind (their own CTest entries, which
// require the report): kernels with an out-of-bounds write and an
// uninitialised value.
TEST(OclgrindControl, DISABLED_WritePastTheEnd) {
    Kernel k = test::device().kernel(test::test_program("oclgrind_control.cl", "-cl-std=CL1.2"),
                                     "control_write_past_end");
    Buffer out = out_buffer<std::uint32_t>(kN);
    k.arg(0, out).arg(1, kN);
    test::run(k, kN + 1);
}

TEST(OclgrindControl, DISABLED_StoreUninitialised) {
    Kernel k = test::device().kernel(test::test_program("oclgrind_control.cl", "-cl-std=CL1.2"),
                                     "control_store_uninitialised");
    Buffer out = out_buffer<std::uint32_t>(kN);
    k.arg(0, out).arg(1, kN);
    test::run(k, kN);
}

// Oclgrind 21.10's runtime keeps its API-call stack in a thread_local, which
// exit() destroys before static objects; an OpenCL call from a static's
// destructor (the test programs' and the context's release) then writes to
// freed memory (valgrind: "Invalid write of size 8" in clReleaseProgram and
// clFinish, into a block freed by __call_tls_dtors), and glibc aborts on the
// corrupted heap. The checks end the process once every test has run,
// without those releases.
int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
    const int rc = RUN_ALL_TESTS();
    std::fflush(nullptr);
    std::_Exit(rc);
}
