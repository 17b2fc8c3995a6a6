// Ear clipping of OBJ polygons: concave faces stay inside their outline,
// winding is kept, repeated corners do not lose a face.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "scene/memory_files.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/load/polygon_triangulation.hpp"
#include "scene/load/scene_file.hpp"

namespace clpath {
namespace {

using Tris = std::vector<std::array<std::size_t, 3>>;

double area(const std::vector<glm::vec3>& p, const Tris& tris) {
    double a = 0;
    for (const auto& t : tris) a += 0.5 * glm::length(glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]));
    return a;
}

// Every triangle's centroid must lie inside the polygon (even-odd rule in the z = 0 plane).
bool inside_xy(const std::vector<glm::vec3>& poly, glm::vec3 q) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y > q.y) != (poly[j].y > q.y) &&
            q.x < (poly[j].x - poly[i].x) * (q.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            in = !in;
    return in;
}

void expect_inside(const std::vector<glm::vec3>& poly, const Tris& tris) {
    for (const auto& t : tris) {
        const glm::vec3 c = (poly[t[0]] + poly[t[1]] + poly[t[2]]) / 3.0f;
        EXPECT_TRUE(inside_xy(poly, c)) << "triangle " << t[0] << " " << t[1] << " " << t[2] << " lies outside";
        // Wound as the polygon (counter-clockwise seen from +z).
        EXPECT_GT(glm::cross(poly[t[1]] - poly[t[0]], poly[t[2]] - poly[t[0]]).z, 0.0f);
    }
}

TEST(PolygonTriangulation, ConcaveQuadIsCutAtItsReflexCorner) {
    // A dart: corner 2 is reflex. The shorter diagonal 1-3 (length 1 against
    // 1.5 for 0-2) runs outside the dart, so cutting along it (tinyobjloader's
    // rule for quads) would cover 1.25 instead of the dart's 0.75.
    const std::vector<glm::vec3> dart{{0, 0, 0}, {2, -0.5f, 0}, {1.5f, 0, 0}, {2, 0.5f, 0}};
    const Tris t = triangulate_polygon(dart);
    ASSERT_EQ(t.size(), 2u);
    expect_inside(dart, t);
    EXPECT_NEAR(area(dart, t), 0.75, 1e-5);
}

TEST(PolygonTriangulation, ConcaveStarAndCombKeepTheirArea) {
    std::vector<glm::vec3> star;
    for (int i = 0; i < 10; ++i) {
        const float r = i % 2 ? 0.4f : 1.0f, a = float(i) * 3.14159265f / 5;
        star.push_back({r * std::cos(a), r * std::sin(a), 0});
    }
    double shoelace = 0;
    for (std::size_t i = 0; i < star.size(); ++i) {
        const auto& a = star[i];
        const auto& b = star[(i + 1) % star.size()];
        shoelace += 0.5 * (double(a.x) * b.y - double(b.x) * a.y);
    }
    const Tris t = triangulate_polygon(star);
    ASSERT_EQ(t.size(), 8u);
    expect_inside(star, t);
    EXPECT_NEAR(area(star, t), shoelace, 1e-5);

    // A comb of three teeth: many reflex corners in a row.
    const std::vector<glm::vec3> comb{{0, 0, 0}, {5, 0, 0}, {5, 3, 0}, {4, 3, 0}, {4, 1, 0},
                                      {3, 1, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0},
                                      {1, 3, 0}, {0, 3, 0}};
    const Tris c = triangulate_polygon(comb);
    ASSERT_EQ(c.size(), 10u);
    expect_inside(comb, c);
    EXPECT_NEAR(area(comb, c), 5 + 3 * 2, 1e-5);
}

TEST(PolygonTriangulation, WorksInAnyPlaneAndKeepsWinding) {
    // The dart turned into the YZ plane, facing +x: every triangle faces +x too.
    const std::vector<glm::vec3> dart{{0, 0, 0}, {0, 2, -0.5f}, {0, 1.5f, 0}, {0, 2, 0.5f}};
    const Tris t = triangulate_polygon(dart);
    ASSERT_EQ(t.size(), 2u);
    for (const auto& tri : t)
        EXPECT_GT(glm::cross(dart[tri[1]] - dart[tri[0]], dart[tri[2]] - dart[tri[0]]).x, 0.0f);
    EXPECT_NEAR(area(dart, t), 0.75, 1e-5);
}

TEST(PolygonTriangulation, RepeatedCornersAreDropped) {
    const std::vector<glm::vec3> q{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}};
    const Tris t = triangulate_polygon(q);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_NEAR(area(q, t), 0.5, 1e-6);
}

// An outline gone round several times (assimp's box_longline.obj: a square
// written 234 times over in one face) is the face once, every triangle
// facing the way the outline winds.
TEST(PolygonTriangulation, OutlineGoneRoundTwiceOrMoreIsTheFaceOnce) {
    const std::vector<glm::vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int rounds : {2, 3, 234}) {
        std::vector<glm::vec3> q;
        for (int r = 0; r < rounds; ++r) q.insert(q.end(), square.begin(), square.end());
        const Tris t = triangulate_polygon(q);
        ASSERT_EQ(t.size(), 2u) << rounds;
        expect_inside(square, t);
        EXPECT_NEAR(area(q, t), 1.0, 1e-6);
    }
    // A keyhole (an outer square and an inner one joined by a bridge walked
    // both ways) repeats corners but is no repeat of a shorter outline: its
    // hole stays open.
    const std::vector<glm::vec3> keyhole{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0}, {1, 1, 0},
                                         {1, 3, 0}, {3, 3, 0}, {3, 1, 0}, {1, 1, 0}};
    const Tris k = triangulate_polygon(keyhole);
    EXPECT_NEAR(area(keyhole, k), 16.0 - 4.0, 1e-5);
}

TEST(ObjPolygons, ConcaveFaceInAFileCoversItsOwnArea) {
    test::MemoryFiles files;
    // The dart as one OBJ face: what reaches the scene covers exactly its area.
    const ObjMesh m = parse_obj("v 0 0 0\nv 2 -0.5 0\nv 1.5 0 0\nv 2 0.5 0\nf 1 2 3 4\n", "m/dart.obj",
                                files.options().read_file);
    ASSERT_EQ(m.triangle_count(), 2u);
    double a = 0;
    for (std::size_t t = 0; t < 2; ++t)
        a += 0.5 * glm::length(glm::cross(m.vertices[3 * t + 1] - m.vertices[3 * t], m.vertices[3 * t + 2] - m.vertices[3 * t]));
    EXPECT_NEAR(a, 0.75, 1e-5);
}

// A face of more than 255 corners: tinyobjloader keeps a face's corner count
// in a byte, so a 300-gon would lose 256 corners to the faces after it.
TEST(ObjPolygons, FacesOfMoreThan255CornersStayWhole) {
    std::string obj;
    const int n = 300;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * 3.14159265358979 * i / n;
        obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    obj += "v 5 0 0\nv 6 0 0\nv 5 1 0\nf";
    for (int i = 1; i <= n; ++i) (obj += " ") += std::to_string(i);
    obj += "\nf 301 302 303\n";
    test::MemoryFiles files;
    const ObjMesh m = parse_obj(obj, "m/disc.obj", files.options().read_file);
    ASSERT_EQ(m.triangle_count(), std::size_t(n - 2 + 1));
    double a = 0;
    for (std::size_t t = 0; t + 1 < m.triangle_count(); ++t) {
        const glm::vec3 c = (m.vertices[3 * t] + m.vertices[3 * t + 1] + m.vertices[3 * t + 2]) / 3.0f;
        EXPECT_LT(glm::length(c), 1.0f);  // inside the disc
        a += 0.5 * glm::length(glm::cross(m.vertices[3 * t + 1] - m.vertices[3 * t], m.vertices[3 * t + 2] - m.vertices[3 * t]));
    }
    EXPECT_NEAR(a, 0.5 * n * std::sin(2 * 3.14159265358979 / n), 1e-4);  // the 300-gon's area
    const std::size_t last = m.triangle_count() - 1;
    EXPECT_EQ(m.vertices[3 * last], glm::vec3(5, 0, 0));
    EXPECT_EQ(m.vertices[3 * last + 2], glm::vec3(5, 1, 0));
}

TEST(ObjPolygons, RepeatedCornersKeepTheFace) {
    // "f 1 2 2 3": a triangle written with a repeated corner is still a triangle.
    test::MemoryFiles files;
    files.files["m/rep.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2 3\n";
    const Scene s = obj_scene("m/rep.obj", files.options());
    EXPECT_GE(s.triangle_count(), 1u);
    // Only repeats: refused as degenerate, not as a file without faces.
    files.files["m/rep.obj"] = "v 0 0 0\nv 1 0 0\nf 1 2 2 1\n";
    EXPECT_EQ(test::error_of([&] { obj_scene("m/rep.obj", files.options()); }),
              "m/rep.obj: every triangle is degenerate (an empty scene)");
}

}  // namespace
}  // namespace clpath
