// The two-level structure (bvh/instances.hpp): layout, offsets and the
// transforms' checks. Traversal against flattened geometry is tested with the
// real kernels in tests/render/instancing_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/instances.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {

std::vector<glm::vec3> strip(int n, float z) {
    std::vector<glm::vec3> v;
    for (int i = 0; i < n; ++i) v.insert(v.end(), {{float(i), 0, z}, {float(i) + 1, 0, z}, {float(i), 1, z}});
    return v;
}

TEST(BvhInstances, LayoutRecordsAndOffsets) {
    const auto a = strip(40, 0), b = strip(3, 1);
    const glm::mat4 mirror = glm::scale(glm::mat4(1), {-2, 1, 0.5f});
    const std::vector<InstanceInput> inst{{0, glm::mat4(1)}, {1, glm::translate(glm::mat4(1), {5, 0, 0})}, {0, mirror}};
    const TwoLevelBvh t = build_two_level({&a, &b}, {0, 40}, inst);
    EXPECT_EQ(t.triangles.size(), 43u);
    EXPECT_EQ(t.stats.instances, 3u);
    EXPECT_EQ(t.stats.placed_triangles, 83u);
    const std::size_t records = t.stats.top_nodes;
    // Every top-level leaf names a record; every record's root is a node past the records.
    std::vector<int> seen(3, 0);
    for (std::size_t n = 0; n < records; ++n)
        for (int s = 0; s < 4; ++s)
            if (t.nodes[n].child[s] < 0) {
                const int rec = ~t.nodes[n].child[s];
                ASSERT_GE(rec, int(records));
                ASSERT_LT(rec, int(records + 3));
                ++seen[std::size_t(rec) - records];
            }
    EXPECT_EQ(seen, std::vector<int>({1, 1, 1}));
    for (std::size_t i = 0; i < 3; ++i) {
        Instance r;
        std::memcpy(&r, &t.nodes[records + i], sizeof r);
        EXPECT_GE(r.blas_root, records + 3);
        EXPECT_EQ(r.mesh, inst[i].mesh);
        EXPECT_EQ(r.first_prim, inst[i].mesh == 0 ? 0u : 40u);
        EXPECT_EQ(r.det_sign, i == 2 ? -1.0f : 1.0f);
        // world_to_object undoes object_to_world.
        const glm::vec3 p(0.3f, -1.7f, 2.5f);
        glm::vec3 w, o;
        for (int k = 0; k < 3; ++k)
            w[k] = r.object_to_world[4 * k] * p.x + r.object_to_world[4 * k + 1] * p.y + r.object_to_world[4 * k + 2] * p.z +
                   r.object_to_world[4 * k + 3];
        for (int k = 0; k < 3; ++k)
            o[k] = r.world_to_object[4 * k] * w.x + r.world_to_object[4 * k + 1] * w.y + r.world_to_object[4 * k + 2] * w.z +
                   r.world_to_object[4 * k + 3];
        EXPECT_NEAR(glm::length(o - p), 0.0f, 1e-5f);
    }
    // Bottom-level leaves index the shared triangle buffer, interior children the shared node buffer.
    for (std::size_t n = records + 3; n < t.nodes.size(); ++n)
        for (int s = 0; s < 4; ++s) {
            const int c = t.nodes[n].child[s];
            if (c > 0) {
                EXPECT_LT(std::size_t(c), t.nodes.size());
            } else if (c < 0) {
                EXPECT_LE(std::size_t(~c) + t.nodes[n].count[s], t.triangles.size());
            }
        }
    for (const auto& tri : t.triangles) EXPECT_EQ(tri.light, CLP_NO_LIGHT);
}

TEST(BvhInstances, BadTransformsAndMeshesAreRefused) {
    const auto a = strip(4, 0);
    auto error = [&](const std::vector<InstanceInput>& inst) {
        try {
            build_two_level({&a}, {0}, inst);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error({{0, glm::scale(glm::mat4(1), {1, 0, 1})}}).find("instance 0: the transform is singular"),
              std::string::npos);
    glm::mat4 projective(1);
    projective[0][3] = 0.5f;
    EXPECT_NE(error({{0, glm::mat4(1)}, {0, projective}}).find("instance 1: the transform is not affine"), std::string::npos);
    glm::mat4 nan(1);
    nan[3][0] = NAN;
    EXPECT_NE(error({{0, nan}}).find("non-finite"), std::string::npos);
    EXPECT_NE(error({{3, glm::mat4(1)}}).find("names mesh 3"), std::string::npos);
    EXPECT_NE(error({}).find("no instances"), std::string::npos);
}

TEST(BvhInstances, TenThousandInstancesStayShallow) {
    const auto a = strip(2, 0);
    std::vector<InstanceInput> inst;
    for (int i = 0; i < 10000; ++i)
        inst.push_back({0, glm::translate(glm::mat4(1), {float(i % 100) * 3, 0, float(i / 100) * 3})});
    const TwoLevelBvh t = build_two_level({&a}, {0}, inst);
    EXPECT_LE(t.stats.top_depth + t.stats.bottom_depth, CLP_INSTANCE_MAX_DEPTH4);
    EXPECT_EQ(t.stats.top_bytes, (t.stats.top_nodes + 10000) * sizeof(Bvh4Node128));
}

// Triangles, and instances, each twice the size of the last and twice as
// far out: the binned SAH splits only a few off per level (its bins are
// even, the sizes not), so both levels are deep, and together they pass the
// one stack's bound.
TEST(BvhInstances, TopAndBottomTooDeepTogetherAreRefusedNamingBothDepths) {
    std::vector<glm::vec3> a;
    for (int i = 0; i < 50; ++i) {
        const float s = std::ldexp(1.0f, i);
        a.insert(a.end(), {{100 * s, 0, 0}, {101 * s, 0, 0}, {100 * s, s, 0}});
    }
    std::vector<InstanceInput> inst;
    for (int i = 0; i < 60; ++i) {
        const float s = std::ldexp(1.0f, i);
        inst.push_back({0, glm::scale(glm::translate(glm::mat4(1), {100 * s, 0, 0}), glm::vec3(s))});
    }
    try {
        const TwoLevelBvh deep = build_two_level({&a}, {0}, inst);
        FAIL() << "a two-level BVH deeper than the walk's stack was built: " << deep.stats.top_depth << " + "
               << deep.stats.bottom_depth;
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("over 60 instances"), std::string::npos) << m;
        EXPECT_NE(m.find("4-wide levels deep and the deepest placed mesh's"), std::string::npos) << m;
        EXPECT_NE(m.find("together more than the " + std::to_string(CLP_INSTANCE_MAX_DEPTH4)), std::string::npos) << m;
    }
    // The first 8 of them fit.
    inst.resize(8);
    const TwoLevelBvh t = build_two_level({&a}, {0}, inst);
    EXPECT_LE(t.stats.top_depth + t.stats.bottom_depth, CLP_INSTANCE_MAX_DEPTH4);
    EXPECT_GT(t.stats.bottom_depth, 1);
    // One more, placed past the float range, is named.
    inst.push_back({0, glm::scale(glm::mat4(1), glm::vec3(0x1p100f))});
    try {
        build_two_level({&a}, {0}, inst);
        FAIL() << "an instance past the float range was placed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("instance 8: its transform places mesh 0 beyond the float range"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
