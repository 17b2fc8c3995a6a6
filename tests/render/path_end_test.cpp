// Where a path ends (kernels/path.cl path_next_ray_gathers): in a program
// compiled without emission or an environment, the ray a path would take
// from the vertex one short of the deepest is not traced, as it could add
// no light. Checked against the same kernels compiled with CLP_HAS_EMISSION
// added, which trace that ray and, in a scene whose surfaces emit nothing,
// find nothing at its end: the two give the same image bit for bit and the
// default traces fewer rays, at most one per sample fewer. Both kernel
// shapes. Control: where a surface emits, both trace the same rays.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "render/prepared_scene.hpp"
#include "render/renderer.hpp"
#include "scene/load/scene_loader.hpp"
#include "support/repo_root.hpp"
#include "support/test_device.hpp"

using namespace clpath;

namespace {

constexpr int kWidth = 24, kHeight = 16;
constexpr std::uint32_t kSpp = 4;

Scene small(const std::string& name) {
    Scene s = load_scene((test::repo_root() / "scenes" / (name + ".json")).string());
    s.camera.width = kWidth;
    s.camera.height = kHeight;
    return s;
}

struct Rendered {
    Image image;
    std::uint64_t rays = 0;
};

Rendered render(const Scene& scene, const RenderSettings& st, const KernelVariant& variant) {
    const auto prepared = prepare_scene(scene, st);
    Renderer r(test::device(), *prepared, st, variant);
    r.add_samples(kSpp);
    return {r.resolve(1.0f).linear, r.stats().rays};
}

RenderSettings settings(KernelShape shape, std::uint32_t depth) {
    RenderSettings st;
    st.kernel_shape = shape;
    st.max_depth = depth;
    st.rr_rule = CLP_RR_NONE;
    st.seed = 7;
    return st;
}

const KernelVariant kTraceLastRay{{}, "-DCLP_HAS_EMISSION"};

}  // namespace

TEST(PathEnd, PointLitScenesSkipTheRayThatCannotAddLight) {
    const Scene scene = small("cornell-point");
    const std::uint64_t samples = std::uint64_t(kSpp) * kWidth * kHeight;
    for (KernelShape shape : {KernelShape::Mega, KernelShape::Wavefront})
        for (std::uint32_t depth : {1u, 4u}) {
            SCOPED_TRACE(std::string(kernel_shape_name(shape)) + ", depth " + std::to_string(depth));
            const RenderSettings st = settings(shape, depth);
            const Rendered skips = render(scene, st, {}), traces = render(scene, st, kTraceLastRay);
            ASSERT_EQ(skips.image.rgb.size(), traces.image.rgb.size());
            std::size_t differ = 0;
            for (std::size_t i = 0; i < skips.image.rgb.size(); ++i) differ += skips.image.rgb[i] != traces.image.rgb[i];
            EXPECT_EQ(differ, 0u) << "values that differ";
            EXPECT_LT(skips.rays, traces.rays);
            EXPECT_LE(traces.rays - skips.rays, samples);
        }
}

TEST(PathEnd, ScenesWithEmittersTraceEveryRay) {
    const Scene scene = small("cornell-classic");
    for (KernelShape shape : {KernelShape::Mega, KernelShape::Wavefront}) {
        SCOPED_TRACE(kernel_shape_name(shape));
        const RenderSettings st = settings(shape, 4);
        EXPECT_EQ(render(scene, st, {}).rays, render(scene, st, kTraceLastRay).rays);
    }
}
