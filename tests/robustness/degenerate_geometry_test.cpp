// Degenerate geometry (robustness suite, item 4): zero-area, collinear and
// repeated-vertex triangles, triangles smaller than the float spacing at
// their position, triangles of size 1e8, some of them emitting, put into a
// scene directly (the loaders drop such triangles with a warning; the
// renderer must not depend on that). Expected: no crash, zero non-finite
// samples, and the degenerate triangles change nothing: the image equals, in
// distribution, the same scene without them.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/shapes.hpp"
#include "support/image_agreement.hpp"
#include "support/render_helpers.hpp"
#include "support/render_runs.hpp"
#include "support/statistics.hpp"

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
// its area (2e16) and the light-sampling pdf stay finite in float, the
// light sampled is at distance up to 1e8 (distance^2 1e16): no overflow.
//
// Expected, in closed form: the floor (albedo rho, the square |x|, |z| <= 5
// at y = 0) has radiance rho Le F, F the form factor from a floor point to the
// triangle (Le = 1, one-sided, facing down at height h = 1e3). The triangle
// contains the disk of radius r about the point above any floor point, r = the
// distance from the origin to the triangle's nearest edge (1e8 / sqrt 5) less
// the floor's half-diagonal; a disk of radius r at height h has F = r^2 / (r^2
// + h^2), so 1 - F < h^2 / r^2 = 5e-10. Paths end at the emitter (albedo 0)
// or in the black sky; the floor cannot see itself. So a pixel whose whole
// footprint lies on the floor has expectation rho Le to 5e-10, and one whose
// whole footprint misses the floor is exactly 0 (camera rays all point down
// and meet nothing). Each sample of next-event estimation with MIS is at most
// rho Le (BSDF-sampled hits, weight <= 1) + rho Le / 2 (light samples: the
// power heuristic's w / p_light <= 1 / (2 p_bsdf)), so non-finite or huge
// values from the 1e8 distances would show.
TEST(DegenerateGeometry, HugeEmitter) {
    const double rho = 0.5, le = 1.0, h = 1e3, half = 5;
    Scene s;
    s.name = "huge";
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, glm::vec3(2 * half))),
                    s.add_material("floor", diffuse(glm::vec3(rho))));
    s.add_triangles({glm::vec3(-1e8f, h, -1e8f), glm::vec3(1e8f, h, -1e8f), glm::vec3(0, h, 1e8f)},  // facing down
                    s.add_material("sky", emitter(glm::vec3(le))));
    s.camera.eye = {0, 2, -3};
    s.camera.target = {0, 0, 0};
    s.camera.width = s.camera.height = 16;
    RenderSettings st;
    st.max_depth = 6;
    RenderStats stats;
    const Image img = test::render(s, st, 32, &stats).linear;
    EXPECT_EQ(stats.nonfinite, 0u);

    const double r = 1e8 / std::sqrt(5.0) - half * std::sqrt(2.0);
    const double form_factor_gap = h * h / (r * r);
    // Where the rays through a pixel's four corners meet the floor's plane
    // (the kernels' camera: x, y in [-1, 1] across the film, row 0 at the top).
    const CameraData cd = camera_data(s.camera);
    const glm::dvec3 eye(load3(cd.eye)), f(load3(cd.forward)), right(load3(cd.right)), up(load3(cd.up));
    auto on_plane = [&](double fx, double fy) {
        const glm::dvec3 d = f + (2 * fx / img.width - 1) * right + (1 - 2 * fy / img.height) * up;
        return eye + d * (eye.y / -d.y);  // every ray of this view points down
    };
    std::vector<double> on_floor;
    std::size_t off_floor = 0;
    for (int py = 0; py < img.height; ++py)
        for (int px = 0; px < img.width; ++px) {
            int inside = 0, beyond = 0;
            for (int k = 0; k < 4; ++k) {
                const glm::dvec3 p = on_plane(px + k % 2, py + k / 2);
                inside += std::abs(p.x) < half && std::abs(p.z) < half;
                beyond += p.z > half;  // past the far edge (the only edge this view crosses)
            }
            const float v = img.rgb[3 * (std::size_t(py) * img.width + px)];
            if (inside == 4) on_floor.push_back(v);  // the footprint is convex, and so is the floor
            if (beyond == 4) {
                EXPECT_EQ(v, 0.0f) << "pixel " << px << ", " << py << " sees only the black sky";
                ++off_floor;
            }
            EXPECT_LE(v, 1.5 * rho * le) << "pixel " << px << ", " << py << ": above the bound of every sample";
        }
    ASSERT_GT(on_floor.size(), 100u);
    ASSERT_GT(off_floor, 10u);
    // Pixels are independent estimates of rho Le (1 - gap): alpha 1e-6, plus
    // the gap and float rounding (about 16 roundings along the path and in the film).
    const auto m = test::mean_error(on_floor);
    EXPECT_NEAR(m.mean, rho * le, test::normal_quantile_two_sided(1e-6) * m.std_error +
                                      rho * le * (form_factor_gap + 16 * 0x1.0p-24))
        << "+- " << m.std_error << " over " << on_floor.size() << " pixels";
}
