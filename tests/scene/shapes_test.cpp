// Built-in shapes: sizes, triangle counts, outward-facing triangles and normals.
#include <gtest/gtest.h>

#include "scene/scene_builder.hpp"
#include "scene/shapes.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// Every triangle of a closed shape around the origin faces away from it.
void expect_outward(const std::vector<glm::vec3>& v, const char* what) {
    for (std::size_t t = 0; t + 2 < v.size(); t += 3) {
        const glm::vec3 n = glm::cross(v[t + 1] - v[t], v[t + 2] - v[t]);
        ASSERT_GT(glm::dot(n, v[t] + v[t + 1] + v[t + 2]), 0.0f) << what << " triangle " << t / 3;
    }
}

TEST(Shapes, UvSphereHitsTheRequestedCount) {
    for (std::size_t want : {12u, 100u, 1000u, 12345u, 1000000u}) {
        const auto [rings, segments] = uv_sphere_resolution(want);
        const std::size_t got = std::size_t(2) * segments * (rings - 1);
        EXPECT_NEAR(double(got), double(want), 0.02 * double(want) + 8) << want;
    }
    const ShapeMesh s = make_uv_sphere(1000);
    EXPECT_EQ(s.triangle_count(), s.vertices.size() / 3);
    EXPECT_EQ(s.normals.size(), s.vertices.size());
    for (auto v : s.vertices) EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
    expect_outward(s.vertices, "uv sphere");
    for (std::size_t i = 0; i < s.vertices.size(); ++i) EXPECT_NEAR(glm::dot(s.normals[i], s.vertices[i]), 1.0f, 1e-5f);
}

TEST(Shapes, UvSphereHasNoDegenerateTriangles) {
    const ShapeMesh s = make_uv_sphere(5000);
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        EXPECT_FALSE(is_degenerate(s.vertices[3 * t], s.vertices[3 * t + 1], s.vertices[3 * t + 2])) << t;
}

TEST(Shapes, BumpySphereStaysCloseAndOutward) {
    Bumps b;
    b.kind = Bumps::Kind::Sine;
    b.amplitude = 0.1f;
    b.frequency = 2;
    const ShapeMesh s = make_uv_sphere(20000, b);
    float lo = 2, hi = 0;
    for (auto v : s.vertices) {
        lo = std::min(lo, glm::length(v));
        hi = std::max(hi, glm::length(v));
    }
    EXPECT_GT(lo, 0.89f);
    EXPECT_LT(hi, 1.11f);
    EXPECT_GT(hi - lo, 0.1f);  // it is bumpy
    expect_outward(s.vertices, "bumpy sphere");
    for (auto n : s.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
}

TEST(Shapes, GridFacesUpAndFollowsItsHeight) {
    const ShapeMesh flat = make_grid(3, 5);
    EXPECT_EQ(flat.triangle_count(), 30u);
    for (std::size_t t = 0; t < flat.triangle_count(); ++t) {
        const glm::vec3 n = flat_normal(flat.vertices[3 * t], flat.vertices[3 * t + 1], flat.vertices[3 * t + 2]);
        EXPECT_NEAR(n.y, 1.0f, 1e-6f);
    }
    for (auto v : flat.vertices) {
        EXPECT_LE(std::abs(v.x), 0.5f);
        EXPECT_LE(std::abs(v.z), 0.5f);
    }
    Bumps h;
    h.kind = Bumps::Kind::Ripple;
    h.amplitude = 0.2f;
    h.frequency = 1;
    const ShapeMesh rip = make_grid(10, 10, h);
    // At the centre, cos(0) = 1: height = amplitude.
    bool centre = false;
    for (auto v : rip.vertices)
        if (v.x == 0 && v.z == 0) {
            EXPECT_FLOAT_EQ(v.y, 0.2f);
            centre = true;
        }
    EXPECT_TRUE(centre);
}

// Out-of-range parameters are the one user-facing error type (util/error.hpp),
// whose message the program prints as "clpath: error: ...", never an internal error.
TEST(Shapes, BadParametersAreUserErrors) {
    auto message = [](auto make) -> std::string {
        try {
            make();
        } catch (const Error& e) {
            return e.what();
        } catch (const std::exception& e) {
            return std::string("not a clpath::Error: ") + e.what();
        }
        return "no error";
    };
    EXPECT_EQ(message([] { make_grid(0, 3); }), "grid: the resolution must be at least 1 x 1 cells, got 0 x 3");
    EXPECT_EQ(message([] { make_icosphere(11); }), "icosphere: the subdivision level must be in [0, 10], got 11");
    EXPECT_EQ(message([] { make_smooth_icosphere(-1); }),
              "icosphere: the subdivision level must be in [0, 10], got -1");
}

TEST(Shapes, IcosphereNormalsArePositions) {
    const ShapeMesh s = make_smooth_icosphere(2);
    EXPECT_EQ(s.triangle_count(), 320u);
    expect_outward(s.vertices, "icosphere");
    EXPECT_EQ(s.normals, s.vertices);
}

TEST(Shapes, DegenerateTest) {
    const glm::vec3 a(0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_FALSE(is_degenerate(a, b, c));
    EXPECT_TRUE(is_degenerate(a, a, c));                    // repeated vertex
    EXPECT_TRUE(is_degenerate(a, b, glm::vec3(2, 0, 0)));   // collinear
    EXPECT_TRUE(is_degenerate(a, b, glm::vec3(NAN, 0, 0)));  // non-finite
    EXPECT_TRUE(is_degenerate(a, b, glm::vec3(INFINITY, 0, 0)));
    // Tiny but well-shaped triangles are kept.
    EXPECT_FALSE(is_degenerate(a * 1e-6f, b * 1e-6f, c * 1e-6f));
}

}  // namespace
}  // namespace clpath
