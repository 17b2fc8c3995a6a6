// Instancing (a two-level BVH, kernels/traverse_instances.cl) against the
// same scene flattened (flatten_instances): the same hits and the same image,
// up to float rounding, in both kernel shapes. The scene: the thesis room
// (flat, with its lamp) and a smooth icosphere placed four times: as is,
// mirrored, scaled strongly non-uniformly and turned, and both at once.
//
// Where the bounds come from. The two renders see the same triangles, each
// vertex rounded differently: flattened, M v is rounded once on the host;
// instanced, the ray is moved into object space (W o, W d: four roundings per
// component) and the hit point moved back (instance_hit_point). Each is a
// relative error of a few gamma(4) ~ 2.4e-7 of the magnitudes involved, times
// the transform's condition number (here at most 4: the scale 0.5 .. 2). A
// hit's distance and normal so differ by well under 1e-5 relative (kRel); a
// ray within that of a triangle's edge may take the neighbour in one render
// and not the other, which changes its pixel wholesale: such rays are
// counted, not bounded, and must be a handful (kEdgeShare of the pixels: with
// the edges' total length in pixels under 2000 and a band of 1e-5 relative
// width around each, the expected count is far below one pixel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "render/kernel_features.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/shapes.hpp"
#include "support/render_helpers.hpp"

using namespace clpath;

namespace {

constexpr double kRel = 1e-5;
constexpr double kEdgeShare = 0.002;

glm::mat4 place(glm::vec3 t, glm::vec3 rot_deg, glm::vec3 s) {
    return shape_transform(t, glm::radians(rot_deg), s);
}

// The room with four instances of a smooth icosphere (radius 1 in object space).
Scene instanced_room(int width, int height) {
    Scene s = test::small_cornell(width, height);
    const ShapeMesh ball = make_smooth_icosphere(2);
    InstancedMesh mesh;
    mesh.name = "ball";
    mesh.vertices = ball.vertices;
    mesh.normals = ball.normals;
    mesh.triangle_material.assign(ball.vertices.size() / 3, 0);  // "default", white diffuse
    s.meshes.push_back(mesh);
    s.instances.push_back({0, place({-0.25f, 0.05f, -0.25f}, {0, 0, 0}, glm::vec3(0.1f))});
    s.instances.push_back({0, place({0.2f, 0.05f, -0.3f}, {0, 30, 0}, {-0.1f, 0.1f, 0.1f})});    // mirrored
    s.instances.push_back({0, place({0.0f, 0.55f, 0.0f}, {20, 40, 10}, {0.2f, 0.05f, 0.12f})});  // 4:1 squashed
    s.instances.push_back({0, place({-0.1f, 0.3f, 0.25f}, {0, -50, 35}, {0.06f, 0.2f, -0.1f})}); // both
    return s;
}

struct Agreement {
    std::size_t pixels = 0, beyond = 0;
    double worst = 0;  // largest relative difference among pixels within the bound
};

// Per pixel, the largest channel difference relative to max(1, |value|)
// (depth, normals in [0, 1] and radiance alike): within kRel, or counted beyond.
Agreement agreement(const Image& a, const Image& b, double rel = kRel) {
    Agreement g;
    g.pixels = std::size_t(a.width) * a.height;
    for (std::size_t p = 0; p < g.pixels; ++p) {
        double d = 0;
        for (int c = 0; c < 3; ++c) {
            const double x = a.rgb[3 * p + c], y = b.rgb[3 * p + c];
            d = std::max(d, std::abs(x - y) / std::max({1.0, std::abs(x), std::abs(y)}));
        }
        if (d > rel) ++g.beyond;
        else g.worst = std::max(g.worst, d);
    }
    return g;
}

RenderSettings settings_for(std::uint32_t integrator, KernelShape shape) {
    RenderSettings st;
    st.integrator = integrator;
    st.kernel_shape = shape;
    st.seed = 11;
    st.max_depth = 6;
    return st;
}

void expect_agree(const Scene& a, const Scene& b, std::uint32_t integrator, KernelShape shape, std::uint32_t spp,
                  double rel = kRel) {
    const RenderSettings st = settings_for(integrator, shape);
    const Image ia = test::render(a, st, spp).linear;
    const Image ib = test::render(b, st, spp).linear;
    ASSERT_EQ(ia.rgb.size(), ib.rgb.size());
    const Agreement g = agreement(ia, ib, rel);
    EXPECT_LE(double(g.beyond), kEdgeShare * double(g.pixels))
        << integrator_name(integrator) << " " << kernel_shape_name(shape) << ": " << g.beyond << " of " << g.pixels
        << " pixels differ by more than " << rel << " (relative)";
    std::printf("%s %s: %zu of %zu pixels beyond %g; worst within %.3g\n", integrator_name(integrator),
                kernel_shape_name(shape), g.beyond, g.pixels, rel, g.worst);
}

TEST(Instancing, HitsMatchTheFlattenedScene) {
    // Depth: each camera ray's t; normals: the shading normal through the
    // inverse transpose; albedo: the same triangle's material. One sample,
    // the megakernel (the one-bounce views have no wavefront shape).
    const Scene inst = instanced_room(96, 80);
    const Scene flat = flatten_instances(inst);
    ASSERT_TRUE(flat.instances.empty());
    ASSERT_EQ(flat.triangle_count(), inst.placed_triangle_count());
    for (std::uint32_t integrator : {CLP_INTEGRATOR_DEPTH, CLP_INTEGRATOR_NORMALS, CLP_INTEGRATOR_ALBEDO})
        expect_agree(inst, flat, integrator, KernelShape::Mega, 1);
}

TEST(Instancing, PathImagesMatchTheFlattenedSceneInBothShapes) {
    // Same seed: every path makes the same choices, so the images agree
    // pixel by pixel up to the rounding above, except where a path's choice
    // flips on it (a ray at an edge, a roulette draw at its threshold).
    // A path's radiance is a product of a factor per vertex (emission, BSDF,
    // cosine, pdf), each off by at most kRel: the bound is (max_depth + 1) kRel.
    // This is also the spawn offset's check (docs/robustness.md, "Instances"):
    // with the transform's rounding left out of the world error bound
    // (instance_hit_point), bounce rays re-hit the squashed and mirrored
    // balls they leave, and 16 of these pixels differed beyond the bound
    // (PoCL, checked by hand when the bound was added).
    const Scene inst = instanced_room(64, 48);
    const Scene flat = flatten_instances(inst);
    const double rel = kRel * (settings_for(CLP_INTEGRATOR_PATH, KernelShape::Mega).max_depth + 1);
    for (KernelShape shape : {KernelShape::Mega, KernelShape::Wavefront})
        expect_agree(inst, flat, CLP_INTEGRATOR_PATH, shape, 2, rel);
}

TEST(Instancing, ControlNormalsWithoutTheInverseTransposeAreCaught) {
    // The flattened scene made wrongly: normals moved by M itself, as a
    // direction, not by its inverse transpose. Only the non-uniformly scaled
    // instances change; the same comparison must reject it.
    const Scene inst = instanced_room(96, 80);
    Scene wrong = inst;
    for (auto& in : wrong.instances) {
        InstancedMesh m = wrong.meshes[in.mesh];
        // Pre-distort the object normals so that the inverse transpose of M
        // applied to them gives M n: n' = M^T M n (normalised).
        const glm::mat3 l(in.object_to_world);
        for (auto& n : m.normals) n = glm::normalize(glm::transpose(l) * (l * n));
        in.mesh = std::uint32_t(wrong.meshes.size());
        wrong.meshes.push_back(m);
    }
    const Scene flat_wrong = flatten_instances(wrong);
    const RenderSettings st = settings_for(CLP_INTEGRATOR_NORMALS, KernelShape::Mega);
    const Agreement g = agreement(test::render(inst, st, 1).linear, test::render(flat_wrong, st, 1).linear);
    EXPECT_GT(double(g.beyond), 20 * kEdgeShare * double(g.pixels))
        << "normals moved by M instead of its inverse transpose went unnoticed: " << g.beyond << " of " << g.pixels;
}

// A normal map's texture: tangent-space normals tilted both ways along
// both axes, so the frame's tangent and its bitangent's sign both show;
// smooth (one period), so a lookup magnifies rounding little (lookup_gain).
Texture bumps() {
    Texture t;
    t.name = "bumps";
    t.width = t.height = 16;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const float a = 0.3926991f;  // 2 pi / 16: one period across the (repeating) texture
            const glm::vec3 n = glm::normalize(glm::vec3(0.6f * std::sin(a * float(x)), 0.6f * std::cos(a * float(y)), 1.0f));
            for (int c = 0; c < 3; ++c) t.rgba8.push_back(std::uint8_t(std::lround(127.5f * (n[c] + 1.0f))));
            t.rgba8.push_back(255);
        }
    return t;
}

Texture checker() {
    Texture t;
    t.name = "checker";
    t.width = t.height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool on = (x + y) % 2 == 0;
            t.rgba8.insert(t.rgba8.end(), {std::uint8_t(on ? 170 : 100), std::uint8_t(on ? 150 : 110), 128, 255});
        }
    return t;
}

// The room with two textured, normal-mapped spheres placed by instances:
// mesh 0 with texture coordinates and its own tangents (bitangent signs
// alternating by triangle), mesh 1 with texture coordinates and vertex
// colours, its tangents derived from the coordinates. Each placed as is,
// mirrored, squashed and turned; `mirrored` lists the mirroring instances.
Scene textured_instanced_room(int width, int height, std::vector<std::size_t>* mirrored = nullptr) {
    Scene s = test::small_cornell(width, height);
    s.textures = {checker(), bumps()};
    SceneMaterial m = gltf_material(glm::vec3(1), 0.0f, 0.6f);
    m.texture[CLP_TEX_BASE] = 0;
    m.texture[CLP_TEX_NORMAL] = 1;
    const std::uint32_t mat = s.add_material("bumpy checker", m);
    const ShapeMesh ball = make_smooth_icosphere(1);
    for (int k = 0; k < 2; ++k) {
        InstancedMesh mesh;
        mesh.name = k == 0 ? "tangents given" : "tangents derived";
        mesh.vertices = ball.vertices;
        mesh.normals = ball.normals;
        mesh.triangle_material.assign(ball.triangle_count(), mat);
        for (std::size_t i = 0; i < ball.vertices.size(); ++i) {
            const glm::vec3 p = glm::normalize(ball.vertices[i]);
            // Longitude unwrapped per triangle (the texture repeats), so no
            // triangle spans the seam's whole period.
            float u = 2.0f * std::atan2(p.z, p.x) / 3.14159265f;
            if (i % 3) u -= 4.0f * std::round((u - mesh.uvs[i - i % 3].x) / 4.0f);
            mesh.uvs.push_back({u, 2.0f * std::acos(p.y) / 3.14159265f});
            if (k == 0) {
                const glm::vec3 t = glm::cross(glm::vec3(0, 1, 0), p);
                mesh.tangents.push_back(glm::vec4(glm::length(t) > 1e-4f ? glm::normalize(t) : glm::vec3(1, 0, 0),
                                                  (i / 3) % 2 ? -1.0f : 1.0f));
            } else {
                mesh.colors.push_back({0.5f + 0.5f * p.x, 0.5f + 0.5f * p.y, 0.5f + 0.5f * p.z, 1.0f});
            }
        }
        s.meshes.push_back(mesh);
    }
    s.instances.push_back({0, place({-0.25f, 0.12f, -0.25f}, {0, 20, 0}, {0.16f, 0.08f, 0.12f})});   // squashed
    s.instances.push_back({0, place({0.22f, 0.12f, -0.3f}, {0, 30, 0}, {-0.12f, 0.12f, 0.12f})});    // mirrored
    s.instances.push_back({1, place({0.0f, 0.55f, 0.0f}, {20, 40, 10}, {0.2f, 0.07f, 0.12f})});       // squashed
    s.instances.push_back({1, place({-0.1f, 0.3f, 0.25f}, {0, -50, 35}, {0.08f, 0.2f, -0.12f})});     // both
    if (mirrored) *mirrored = {1, 3};
    return s;
}

// How much a texture lookup magnifies the hits' rounding. The two renders
// find a hit's barycentrics off by about kRel times the point's magnitude
// over the triangle's height (the rounding is relative to the coordinates,
// the barycentrics to the triangle); the texture coordinates interpolated
// there move by that times the triangle's span in (u, v), and the filtered
// texture by that times its steepest step between neighbouring texels (per
// unit of u or v: the step times the texture's size; decoded, the base
// colour from sRGB, the normal map to [-1, 1]). The largest product over the
// instanced triangles, in world space; at least 1 (kRel's own terms).
double lookup_gain(const Scene& inst) {
    auto srgb = [](std::uint8_t b) {
        const double c = b / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    double steep = 0;
    for (std::size_t k = 0; k < inst.textures.size(); ++k) {
        const Texture& t = inst.textures[k];
        const bool normal_map = t.name == "bumps";
        auto value = [&](int x, int y, int c) {
            const std::uint8_t b = t.rgba8[4 * (std::size_t((y + t.height) % t.height) * t.width + (x + t.width) % t.width) + c];
            return normal_map ? 2.0 * b / 255.0 : srgb(b);
        };
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x)
                for (int c = 0; c < 3; ++c)
                    steep = std::max({steep, std::abs(value(x + 1, y, c) - value(x, y, c)) * t.width,
                                      std::abs(value(x, y + 1, c) - value(x, y, c)) * t.height});
    }
    double gain = 1;
    for (const MeshInstance& in : inst.instances) {
        const InstancedMesh& m = inst.meshes[in.mesh];
        for (std::size_t t = 0; t < m.triangle_count(); ++t) {
            glm::vec3 w[3];
            double size = 0, span = 0;
            for (int c = 0; c < 3; ++c) {
                w[c] = glm::vec3(in.object_to_world * glm::vec4(m.vertices[3 * t + c], 1));
                size = std::max(size, double(glm::length(w[c])));
                const glm::vec2 d = m.uvs[3 * t + c] - m.uvs[3 * t];
                span = std::max(span, double(std::abs(d.x) + std::abs(d.y)));
            }
            // The shortest height: twice the area over the longest edge.
            const double area2 = glm::length(glm::cross(w[1] - w[0], w[2] - w[0]));
            const double longest = std::max({glm::length(w[1] - w[0]), glm::length(w[2] - w[1]), glm::length(w[0] - w[2])});
            gain = std::max(gain, span * steep * size / (area2 / longest));
        }
    }
    return gain;
}

TEST(Instancing, TexturedMeshesMatchTheFlattenedScene) {
    // The normals view shows the normal-mapped shading normal (the tangent
    // frame moved to world space: kernels/surface_params.cl), the albedo
    // view the texture and vertex colours looked up by the object's
    // coordinates; then paths through both kernel shapes. Each bound is the
    // untextured test's times the lookups' gain (lookup_gain).
    const Scene inst = textured_instanced_room(96, 80);
    const Scene flat = flatten_instances(inst);
    ASSERT_EQ(flat.uvs.size(), flat.vertices.size());
    ASSERT_EQ(flat.tangents.size(), flat.vertices.size());
    ASSERT_EQ(flat.colors.size(), flat.vertices.size());
    const double gain = lookup_gain(inst);
    std::printf("texture lookups magnify the rounding by at most %.1f\n", gain);
    for (std::uint32_t integrator : {CLP_INTEGRATOR_NORMALS, CLP_INTEGRATOR_ALBEDO})
        expect_agree(inst, flat, integrator, KernelShape::Mega, 1, kRel * gain);
    const Scene inst_small = textured_instanced_room(64, 48);
    const Scene flat_small = flatten_instances(inst_small);
    const double rel = kRel * gain * (settings_for(CLP_INTEGRATOR_PATH, KernelShape::Mega).max_depth + 1);
    for (KernelShape shape : {KernelShape::Mega, KernelShape::Wavefront})
        expect_agree(inst_small, flat_small, CLP_INTEGRATOR_PATH, shape, 2, rel);
}

// The flattened copies of mesh 0 (given tangents) made wrongly by `spoil`,
// which gets each copy's transform and its three tangents; the normals
// view must then differ from the instanced render in more pixels than
// TexturedMeshesMatchTheFlattenedScene lets through.
template <class Spoil>
void expect_caught(Spoil spoil, const char* what) {
    const Scene inst = textured_instanced_room(96, 80);
    Scene wrong = flatten_instances(inst);
    const std::uint32_t first_copy = inst.next_object_id();
    for (std::size_t t = 0; t < wrong.triangle_count(); ++t) {
        const std::uint32_t o = wrong.triangle_object[t];
        if (o < first_copy || inst.instances[o - first_copy].mesh != 0) continue;
        spoil(glm::mat3(inst.instances[o - first_copy].object_to_world), &wrong.tangents[3 * t]);
    }
    const RenderSettings st = settings_for(CLP_INTEGRATOR_NORMALS, KernelShape::Mega);
    const Agreement g =
        agreement(test::render(inst, st, 1).linear, test::render(wrong, st, 1).linear, kRel * lookup_gain(inst));
    // Rejected by the agreement test's own rule (expect_agree).
    EXPECT_GT(double(g.beyond), kEdgeShare * double(g.pixels))
        << what << " went unnoticed: " << g.beyond << " of " << g.pixels;
    std::printf("%s: %zu of %zu pixels beyond\n", what, g.beyond, g.pixels);
}

TEST(Instancing, ControlTangentsOfMirroredCopiesUnflippedAreCaught) {
    expect_caught(
        [](const glm::mat3& l, glm::vec4* t) {
            if (glm::determinant(l) < 0)
                for (int c = 0; c < 3; ++c) t[c].w *= -1.0f;
        },
        "mirrored copies' bitangent signs left unflipped");
}

TEST(Instancing, ControlTangentsThroughTheInverseTransposeAreCaught) {
    // Tangents moved as normals are: right for rotations and uniform
    // scales, wrong for the squashed copies.
    expect_caught(
        [](const glm::mat3& l, glm::vec4* t) {
            const glm::mat3 n = glm::transpose(glm::inverse(l)), back = glm::inverse(l);
            for (int c = 0; c < 3; ++c)
                if (glm::length(glm::vec3(t[c])) > 0)
                    t[c] = glm::vec4(glm::normalize(n * (back * glm::vec3(t[c]))), t[c].w);
        },
        "tangents moved by the inverse transpose");
}

TEST(Instancing, ShadowRaysSeeInstances) {
    // The any-hit walk: an ambient-occlusion render (shadow rays only past
    // the first hit) agrees with the flattened scene's as the images do.
    const Scene inst = instanced_room(64, 48);
    expect_agree(inst, flatten_instances(inst), CLP_INTEGRATOR_AO, KernelShape::Mega, 2);
}

TEST(Instancing, ASceneWithoutInstancesCompilesNoInstanceCode) {
    RenderSettings st;
    const SceneFeatures plain = scene_features(test::small_cornell(8, 8));
    EXPECT_EQ(build_options(kernel_features(plain, st)).find("CLP_HAS_INSTANCES"), std::string::npos);
    const SceneFeatures inst = scene_features(instanced_room(8, 8));
    EXPECT_NE(build_options(kernel_features(inst, st)).find("-DCLP_HAS_INSTANCES"), std::string::npos);
}

}  // namespace
