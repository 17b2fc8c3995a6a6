#include "support/analytic_scenes.hpp"

#include <cmath>

#include "scene/shapes.hpp"
#include "support/render_helpers.hpp"
#include "support/statistics.hpp"

namespace clpath::test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Scene furnace_sphere(glm::vec3 albedo, glm::vec3 le) {
    Scene s;
    s.name = "furnace";
    // Two-sided: the camera sees the sphere's inside.
    s.add_triangles(make_icosphere(3), s.add_material("shell", emitter(le, true, albedo)));
    s.camera.eye = {0, 0, 0};
    s.camera.target = {0.3f, 0.2f, 1};
    s.camera.vfov_degrees = 90;
    return s;
}

double furnace_radiance(double le, double albedo, int bounces) {
    return le * (1 - std::pow(albedo, bounces + 1)) / (1 - albedo);
}

void add_floor_and_wall(Scene& s, std::uint32_t material) {
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {100, 1, 100})), material);
    s.add_triangles(transformed(make_plane(), shape_transform({0, 50, 0}, {0, 0, float(-kPi / 2)}, {100, 1, 100})),
                    material);
}

double ao_next_to_wall(double x, double d) {
    const double c = x / d;
    if (c >= 1) return 1.0;
    return 1 - (std::acos(c) - c * std::sqrt(1 - c * c)) / kPi;
}

void expect_sky_furnace(const Scene& s, double factor, std::uint32_t integrator, std::uint32_t seed) {
    RenderSettings st;
    st.integrator = integrator;
    st.max_depth = 64;
    st.seed = seed;
    RenderStats stats;
    const Image img = render(s, st, 64, &stats).linear;
    EXPECT_EQ(stats.nonfinite, 0u);
    const double z = normal_quantile_two_sided(1e-4);
    for (int c = 0; c < 3; ++c) {
        const MeanError m = mean_error(channel(img, c));
        const double expected = factor * s.environment.color[c];
        EXPECT_NEAR(m.mean, expected, z * m.std_error + expected * 256 * 0x1.0p-24)
            << integrator_name(integrator) << ", channel " << c;
    }
}

Scene integer_room() {
    const auto box_at = [](glm::vec3 centre, glm::vec3 size) {
        return transformed(make_box(), shape_transform(centre, {0, 0, 0}, size));
    };
    Scene s;
    s.name = "integer-room";
    const auto white = s.add_material("white", diffuse(glm::vec3(0.75f)));
    const auto red = s.add_material("red", diffuse(glm::vec3(0.7f, 0.1f, 0.1f)));
    const auto lamp = s.add_material("lamp", emitter(glm::vec3(12.0f), true));
    s.add_triangles(box_at({0, 64, 0}, {128, 128, 128}), white);
    s.add_triangles(box_at({-24, 24, 48}, {32, 48, 32}), red);   // touches the floor and the back wall
    s.add_triangles(box_at({48, 16, 48}, {32, 32, 32}), white);  // in the back corner
    s.add_triangles(transformed(make_plane(), shape_transform({0, 120, 0}, {0, 0, 0}, {48, 1, 48})), lamp);
    s.camera.eye = {0, 64, -60};
    s.camera.target = {0, 40, 0};
    s.camera.vfov_degrees = 70;
    s.camera.width = s.camera.height = 32;
    return s;
}

}  // namespace clpath::test
