// Degenerate geometry (robustness suite, item 4): zero-area, collinear and
// repeated-vertex triangles, triangles smaller than the float spacing at
// their position, triangles of size 1e8, some of them emitting, put into a
// scene directly (the loaders drop such triangles with a warning; the
// renderer must not depend on that). Expected: no crash, zero non-finite
// samples, and the degenerate triangles change nothing: the image equals, in
// distribution, the same scene without them.
#include <gtest/gtest.h>

#include "scene/shapes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_runs.hpp"

using namespace clpath;

namespace {

Scene base_room() {
    Scene s;
    s.name = "room";
    const auto white = s.add_material("white", diffuse(glm::vec3(0.7f)));
    s.add_triangles(transformed(make_box(), shape_transform({0, 1, 0}, {0, 0, 0}, glm::vec3(2))), white);
    s.add_triangles(transformed(make_plane(), shape_transform({0, 1.95f, 0}, {3.14159265f, 0, 0}, glm::vec3(0.6f))),
                    s.add_material("lamp", emitter(glm::vec3(6.0f))));
    s.camera.eye = {0.2f, 1, -0.9f};
    s.camera.target = {0, 0.8f, 0};
    s.camera.vfov_degrees = 70;
    s.camera.width = s.camera.height = 24;
    return s;
}

Scene with_degenerates(Scene s) {
    const std::uint32_t white = 0;
    const auto lamp = 1u;  // the emitter: degenerate emitters enter the light table too
    const glm::vec3 p(0.3f, 0.5f, 0.2f);
    for (std::uint32_t m : {white, lamp}) {
        s.add_triangles({p, p, p}, m);                                                   // a point
        s.add_triangles({p, p + glm::vec3(0.1f), p + glm::vec3(0.2f)}, m);               // collinear
        s.add_triangles({p, p, p + glm::vec3(0.1f, 0, 0)}, m);                          // repeated vertex
        // Smaller than the float spacing at its position: at x = 1e6 the spacing is 1/16.
        const glm::vec3 far(1e6f, 0.5f, 0.3f);
        s.add_triangles({far, far + glm::vec3(1e-3f, 0, 0), far + glm::vec3(0, 1e-3f, 0)}, m);
        // Sub-ulp inside the room: the offsets round away to a point or a needle.
        s.add_triangles({p, p + glm::vec3(1e-9f, 0, 0), p + glm::vec3(0, 1e-9f, 0)}, m);
        // Huge: 1e8 on a side, far below the room (seen by no camera ray, hit by escaping rays' bounding boxes).
        s.add_triangles({glm::vec3(-1e8f, -1e3f, -1e8f), glm::vec3(1e8f, -1e3f, -1e8f), glm::vec3(0, -1e3f, 1e8f)}, m);
    }
    return s;
}

}  // namespace

TEST(DegenerateGeometry, RendersWithoutNanAndChangesNothing) {
    RenderSettings st;
    st.max_depth = 6;
    for (auto integrator : {CLP_INTEGRATOR_PATH, CLP_INTEGRATOR_PATH_BSDF}) {
        SCOPED_TRACE(integrator_name(integrator));
        st.integrator = integrator;
        std::uint64_t nonfinite = 0;
        const auto a = test::render_runs(base_room(), st, 16, 8, 1, &nonfinite);
        const auto b = test::render_runs(with_degenerates(base_room()), st, 16, 8, 101, &nonfinite);
        EXPECT_EQ(nonfinite, 0u);
        const auto r = test::pixel_agreement(b, test::reference_from_runs("without degenerates", a));
        EXPECT_TRUE(r.ok()) << r.describe();
    }
}

// A huge emitting triangle (1e8 on a side) as the only light over a floor:
// its area (5e15) and the light-sampling pdf stay finite in float, the
// light sampled is at distance up to 1e8 (distance^2 1e16): no overflow.
TEST(DegenerateGeometry, HugeEmitter) {
    Scene s;
    s.name = "huge";
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(10))),
                    s.add_material("floor", diffuse(glm::vec3(0.5f))));
    s.add_triangles({glm::vec3(-1e8f, 1e3f, -1e8f), glm::vec3(1e8f, 1e3f, -1e8f), glm::vec3(0, 1e3f, 1e8f)},  // facing down
                    s.add_material("sky", emitter(glm::vec3(1.0f))));
    s.camera.eye = {0, 2, -3};
    s.camera.target = {0, 0, 0};
    s.camera.width = s.camera.height = 16;
    RenderSettings st;
    st.max_depth = 6;
    RenderStats stats;
    Renderer r(test::device(), s, st);
    r.add_samples(32);
    const auto img = r.resolve().linear;
    EXPECT_EQ(r.stats().nonfinite, 0u);
    // The floor sees the emitter over nearly its whole upper hemisphere:
    // radiance ~ rho Le = 0.5 (a little less: the triangle is not infinite).
    double sum = 0;
    for (float v : img.rgb) sum += v;
    EXPECT_GT(sum / img.rgb.size(), 0.3);
    EXPECT_LE(sum / img.rgb.size(), 0.5 * 1.05);
}
