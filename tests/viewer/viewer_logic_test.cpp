// The viewer's small pure pieces: BVH box levels, frame pacing, letterboxing,
// click to focus.
#include <gtest/gtest.h>

#include "bvh/bvh.hpp"
#include "scene/shapes.hpp"
#include "viewer/bvh_boxes.hpp"
#include "viewer/denoise_pacing.hpp"
#include "viewer/focus_pick.hpp"
#include "viewer/frame_pacer.hpp"
#include "viewer/letterbox.hpp"

using namespace clpath;
using namespace clpath::viewer;

namespace {

void set_child(BvhNode64& n, int i, glm::vec3 lo, glm::vec3 hi, int child, unsigned count) {
    float* l = i ? n.lo1 : n.lo0;
    float* h = i ? n.hi1 : n.hi0;
    for (int a = 0; a < 3; ++a) {
        l[a] = lo[a];
        h[a] = hi[a];
    }
    (i ? n.child1 : n.child0) = child;
    (i ? n.count1 : n.count0) = count;
}

// root -> (node 1, leaf); node 1 -> (leaf, leaf)
BvhNodes three_level_bvh() {
    BvhNodes nodes(2, BvhNode64{});
    set_child(nodes[0], 0, {0, 0, 0}, {1, 1, 1}, 1, 0);
    set_child(nodes[0], 1, {2, 0, 0}, {3, 1, 1}, ~0, 2);
    set_child(nodes[1], 0, {0, 0, 0}, {0.5f, 1, 1}, ~2, 1);
    set_child(nodes[1], 1, {0.5f, 0, 0}, {1, 1, 1}, ~3, 1);
    return nodes;
}

}  // namespace

TEST(ViewerBvhBoxes, LevelsFollowTheTree) {
    const auto nodes = three_level_bvh();
    EXPECT_EQ(bvh_levels(nodes), 2);
    EXPECT_EQ(bvh_boxes(nodes, 0).size(), 0u);
    const auto one = bvh_boxes(nodes, 1);
    ASSERT_EQ(one.size(), 2u);
    for (const auto& b : one) EXPECT_EQ(b.level, 1);
    const auto two = bvh_boxes(nodes, 5);
    ASSERT_EQ(two.size(), 4u);
    int level2 = 0;
    for (const auto& b : two) level2 += b.level == 2;
    EXPECT_EQ(level2, 2);
}

TEST(ViewerBvhBoxes, EmptySlotOfALeafRootIsSkipped) {
    BvhNodes nodes(1, BvhNode64{});
    set_child(nodes[0], 0, {0, 0, 0}, {1, 1, 1}, ~0, 3);
    set_child(nodes[0], 1, {0, 0, 0}, {0, 0, 0}, ~0, 0);
    EXPECT_EQ(bvh_boxes(nodes, 3).size(), 1u);
}

TEST(ViewerBvhBoxes, BoxEdgesAreTheTwelveAxisAlignedEdges) {
    const auto v = box_edges({{0, 0, 0}, {1, 2, 3}, 1});
    ASSERT_EQ(v.size(), 24u);
    glm::vec3 total(0);
    for (std::size_t i = 0; i < v.size(); i += 2) {
        const glm::vec3 d = glm::abs(v[i + 1] - v[i]);
        EXPECT_EQ(int(d.x > 0) + int(d.y > 0) + int(d.z > 0), 1);  // along one axis
        total += d;
    }
    EXPECT_EQ(total, glm::vec3(4, 8, 12));  // four edges per axis
}

TEST(ViewerBvhBoxes, BoxesOfARealBvhContainTheirChildren) {
    std::vector<glm::vec3> tris;
    for (int i = 0; i < 64; ++i) {
        const glm::vec3 o(float(i % 4), float(i / 4 % 4), float(i / 16));
        tris.insert(tris.end(), {o, o + glm::vec3(0.5f, 0, 0), o + glm::vec3(0, 0.5f, 0.2f)});
    }
    const Bvh bvh = build_bvh(tris, BvhBuildOptions{});
    const int levels = bvh_levels(bvh.nodes);
    EXPECT_GE(levels, 2);
    EXPECT_EQ(bvh_boxes(bvh.nodes, levels).size(), bvh_boxes(bvh.nodes, 1 << 20).size());
    EXPECT_LT(bvh_boxes(bvh.nodes, 1).size(), bvh_boxes(bvh.nodes, 2).size());
}

TEST(ViewerFramePacer, FillsTheBudgetWithWholeSamples) {
    FramePacer p(0.031);
    EXPECT_EQ(p.next_samples(), 1u);  // nothing measured
    p.record(2, 0.010);               // 5 ms a sample: 6.2 fit
    EXPECT_EQ(p.next_samples(), 6u);
    p.forget();
    EXPECT_EQ(p.next_samples(), 1u);
    p.record(1, 0.5);  // slower than the budget: still one sample
    EXPECT_EQ(p.next_samples(), 1u);
}

TEST(ViewerDenoisePacing, FirstAtOnceThenByTimeAndSampleGrowth) {
    DenoisePacing p;
    EXPECT_FALSE(p.due(0, 0, false)) << "nothing to denoise";
    EXPECT_TRUE(p.due(0, 4, false)) << "the first image of a view is due at once";
    p.started(4);
    EXPECT_FALSE(p.due(10, 100, false)) << "one at a time";
    p.finished(1.0, 0.1);  // took 0.1 s: the next waits max(0.25, 4 x 0.1) = 0.4 s
    EXPECT_FALSE(p.due(1.3, 100, false)) << "too soon after the last";
    EXPECT_FALSE(p.due(1.5, 4, true)) << "no new samples";
    EXPECT_FALSE(p.due(1.5, 4, false));
    EXPECT_TRUE(p.due(1.5, 5, false)) << "grown by 1.25x";
    EXPECT_TRUE(p.due(1.5, 4 + 1, true));
    p.started(5);
    p.finished(2.0, 0.01);  // fast: the floor of 0.25 s holds
    EXPECT_FALSE(p.due(2.2, 100, false));
    EXPECT_TRUE(p.due(2.3, 100, false));
    EXPECT_TRUE(p.due(2.3, 6, true)) << "the estimate stopped with samples the shown image lacks";
    p.reset();
    EXPECT_TRUE(p.due(2.3, 1, false)) << "a new view is due at once";
}

TEST(ViewerLetterbox, KeepsAspectAndCentres) {
    EXPECT_EQ(letterbox({64, 48}, {64, 48}), glm::ivec4(0, 0, 64, 48));
    EXPECT_EQ(letterbox({64, 48}, {128, 48}), glm::ivec4(32, 0, 64, 48));
    EXPECT_EQ(letterbox({64, 48}, {128, 192}), glm::ivec4(0, 48, 128, 96));
    EXPECT_EQ(letterbox({64, 48}, {0, 10}), glm::ivec4(0));
}

namespace {

// A wall facing the camera at z = 5 and a box in front of it, near the
// image's left edge (image right is -x: forward x up).
std::vector<glm::vec3> focus_scene() {
    auto tris = transformed(make_plane(), shape_transform({0, 0, 5}, {glm::radians(-90.0f), 0, 0}, {20, 1, 20}));
    const auto box = transformed(make_box(), shape_transform({1.5f, 0, 2}, {0, 0, 0}, glm::vec3(1)));
    tris.insert(tris.end(), box.begin(), box.end());
    return tris;
}

Camera focus_camera() {
    Camera c;
    c.eye = {0, 0, 0};
    c.target = {0, 0, 1};
    c.vfov_degrees = 60;
    c.width = 80;
    c.height = 40;
    return c;
}

}  // namespace

TEST(ViewerFocus, DistanceAlongTheViewOfTheSurfaceUnderThePixel) {
    const auto tris = focus_scene();
    const Camera c = focus_camera();
    // The centre sees the wall straight ahead.
    EXPECT_NEAR(*focus_distance_at(tris, c, {40, 20}), 5.0f, 1e-5f);
    // Off-centre the wall is farther along the ray but as far along the view.
    EXPECT_NEAR(*focus_distance_at(tris, c, {70, 5}), 5.0f, 1e-5f);
    // Near the left edge the box's front face, z = 1.5, is nearer.
    EXPECT_NEAR(*focus_distance_at(tris, c, {5, 20}), 1.5f, 1e-5f);
    // Turned away from everything: no surface.
    Camera back = c;
    back.target = {0, 0, -1};
    EXPECT_FALSE(focus_distance_at(tris, back, {40, 20}).has_value());
}

TEST(ViewerFocus, WindowPixelsMapThroughTheLetterbox) {
    // A 100x50 image in a 200x200 framebuffer: 200x100, centred, rows 50..150.
    const glm::ivec4 rect = letterbox({100, 50}, {200, 200});
    const auto p = window_to_image({100, 100}, {1, 1}, {200, 200}, rect, {100, 50});
    ASSERT_TRUE(p.has_value());
    EXPECT_FLOAT_EQ(p->x, 50.0f);
    EXPECT_FLOAT_EQ(p->y, 25.0f);
    const auto corner = window_to_image({0.5f, 50.5f}, {1, 1}, {200, 200}, rect, {100, 50});
    ASSERT_TRUE(corner.has_value());
    EXPECT_FLOAT_EQ(corner->x, 0.25f);
    EXPECT_FLOAT_EQ(corner->y, 0.25f);
    // The bars above and below are not the image.
    EXPECT_FALSE(window_to_image({100, 20}, {1, 1}, {200, 200}, rect, {100, 50}).has_value());
    // A framebuffer of two pixels per window pixel.
    const auto hi = window_to_image({50, 50}, {2, 2}, {200, 200}, rect, {100, 50});
    ASSERT_TRUE(hi.has_value());
    EXPECT_FLOAT_EQ(hi->x, 50.0f);
}
