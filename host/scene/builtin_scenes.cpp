#include "scene/builtin_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/load/load_options.hpp"
#include "scene/load/obj_mesh.hpp"
#include "scene/scene_builder.hpp"
#include "scene/shapes.hpp"
#include "util/error.hpp"

namespace clpath {

Scene cornell_thesis_scene() {
    // Values from the thesis renderer's source, as docs/thesis-scene.md lists them.
    Scene s;
    s.name = "cornell";
    const auto white = s.add_material("default", diffuse({0.740063f, 0.742313f, 0.733934f}));
    const auto red = s.add_material("red", diffuse({0.366046f, 0.0371827f, 0.0416385f}));
    const auto green = s.add_material("green", diffuse({0.162928f, 0.408903f, 0.0833759f}));
    // The thesis lamp is a plane facing up under the ceiling that emits from
    // both sides; it does not reflect.
    const auto lamp = s.add_material("emissive", emitter(glm::vec3(1.0f, 0.93f, 0.85f) * 15.0f, true));

    const float pi = glm::pi<float>();
    auto plane = [&](glm::vec3 pos, glm::vec3 rot, glm::vec2 size, std::uint32_t mat) {
        s.add_triangles(transformed(make_plane(), shape_transform(pos, rot, {size.x, 0, size.y})), mat);
    };
    auto box = [&](glm::vec3 pos, glm::vec3 rot, glm::vec3 size, std::uint32_t mat) {
        s.add_triangles(transformed(make_box(), shape_transform(pos, rot, size)), mat);
    };
    auto sphere = [&](glm::vec3 pos, float radius, int iterations, std::uint32_t mat) {
        s.add_triangles(transformed(make_icosphere(iterations), shape_transform(pos, {0, 0, 0}, glm::vec3(radius))),
                        mat);
    };
    plane({-0.5f, 0.4f, 0}, {0, 0, -pi / 2}, {1, 1}, red);
    plane({0.5f, 0.4f, 0}, {0, 0, pi / 2}, {1, 1}, green);
    plane({0, 0.4f, 0.5f}, {-pi / 2, 0, 0}, {1, 1}, white);
    plane({0, 0.9f, 0}, {pi, 0, 0}, {1, 1}, white);
    plane({0, -0.1f, 0}, {0, 0, 0}, {1, 1}, white);
    plane({0, 0.85f, -0.1f}, {0, 0, 0}, {0.4f, 0.4f}, lamp);
    box({0.3f, 0.1f, 0.1f}, {0, 0.6f, 0}, {0.2f, 0.5f, 0.2f}, white);
    box({-0.2f, 0.15f, 0.1f}, {0, -0.5f, 0}, {0.3f, 0.6f, 0.3f}, white);
    sphere({0, 0.1f, -0.3f}, 0.15f, 1, white);
    sphere({0.3f, 0.45f, 0.1f}, 0.15f, 1, white);

    // The thesis renderer's image has +x on the right (its right = up x forward);
    // clpath's image right is forward x up. Mirroring x shows the same picture,
    // red wall on the left.
    s.vertices = transformed(s.vertices, glm::scale(glm::mat4(1), glm::vec3(-1, 1, 1)));

    s.camera.eye = {0, 0.31f, -1.2f};
    s.camera.target = s.camera.eye + glm::vec3(0, 0, 1);
    s.camera.up = {0, 1, 0};
    s.camera.vfov_degrees = 53.130102f;  // 2 atan(0.5): what the thesis image really spans
    s.camera.width = 800;
    s.camera.height = 640;
    return s;
}

Scene scaling_scene(std::size_t triangles) {
    if (triangles < 100 || triangles > 50'000'000)
        throw Error("scaling:" + std::to_string(triangles) + ": the triangle count must be in [100, 50000000]");
    Scene s = cornell_thesis_scene();
    // The room is the thesis scene's first 12 triangles (five walls and the lamp).
    const std::size_t room = 12;
    s.vertices.resize(room * 3);
    s.triangle_material.resize(room);
    s.triangle_object.resize(room);
    s.name = "scaling";
    // The sphere's bumps stay the same at every count: only the tessellation
    // changes, so the BVH and traversal see the same shape in more pieces.
    Bumps bumps;
    bumps.kind = Bumps::Kind::Sine;
    bumps.amplitude = 0.06f;
    bumps.frequency = 1.5f;
    const ShapeMesh sphere = make_uv_sphere(triangles - room, bumps);
    const std::uint32_t white = 0;  // "default"
    // Where the thesis's front sphere stands, larger, just above the floor; x
    // mirrored like the rest of the built-in scene (it is centred, so no change).
    const glm::mat4 place = shape_transform({0, 0.17f, -0.1f}, {0, 0, 0}, glm::vec3(0.25f));
    s.add_triangles(transformed(sphere.vertices, place), white);
    s.name = "scaling-" + std::to_string(s.triangle_count());
    return s;
}

Scene closed_room_scene(std::size_t triangles) {
    if (triangles < 100 || triangles > 50'000'000)
        throw Error("room:" + std::to_string(triangles) + ": the triangle count must be in [100, 50000000]");
    Scene s;
    const auto white = s.add_material("default", diffuse({0.740063f, 0.742313f, 0.733934f}));
    const auto lamp = s.add_material("emissive", emitter(glm::vec3(1.0f, 0.93f, 0.85f) * 15.0f, true));
    // The thesis room, deepened to z = -1.3 so the camera (z = -1.2) is inside;
    // the cube's triangles face out, so mirroring one axis (which transformed()
    // compensates) would not turn them in: swap the winding by hand.
    auto room = transformed(make_box(), shape_transform({0, 0.4f, -0.4f}, {0, 0, 0}, {1.0f, 1.0f, 1.8f}));
    for (std::size_t i = 0; i + 2 < room.size(); i += 3) std::swap(room[i + 1], room[i + 2]);
    s.add_triangles(room, white);
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0.85f, -0.1f}, {0, 0, 0}, {0.4f, 1, 0.4f})), lamp);
    Bumps bumps;  // as scaling_scene
    bumps.kind = Bumps::Kind::Sine;
    bumps.amplitude = 0.06f;
    bumps.frequency = 1.5f;
    const ShapeMesh sphere = make_uv_sphere(triangles - s.triangle_count(), bumps);
    s.add_triangles(transformed(sphere.vertices, shape_transform({0, 0.17f, -0.1f}, {0, 0, 0}, glm::vec3(0.25f))),
                    white);
    s.camera = cornell_thesis_scene().camera;
    s.name = "room-" + std::to_string(s.triangle_count());
    return s;
}

Scene bunnies_scene(std::size_t instances) {
    if (instances < 1 || instances > 1'000'000)
        throw Error("bunnies:" + std::to_string(instances) + ": the instance count must be in [1, 1000000]");
    const ObjMesh bunny = load_obj(kBunnyFile, read_text_file);
    if (bunny.triangle_count() == 0) throw Error(std::string(kBunnyFile) + ": the mesh has no faces");
    Scene s;
    const auto floor = s.add_material("floor", diffuse({0.55f, 0.55f, 0.5f}));
    const auto fur = s.add_material("bunny", diffuse({0.8f, 0.75f, 0.65f}));
    // The bunny fitted into a unit box standing on y = 0, once.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : bunny.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const float longest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    InstancedMesh mesh;
    mesh.name = std::string("bunny (") + kBunnyFile + ")";
    for (std::size_t t = 0; t < bunny.triangle_count(); ++t) {
        glm::vec3 p[3];
        for (int c = 0; c < 3; ++c) {
            const glm::vec3 v = bunny.vertices[3 * t + std::size_t(c)];
            p[c] = glm::vec3((v.x - 0.5f * (lo.x + hi.x)) / longest, (v.y - lo.y) / longest,
                             (v.z - 0.5f * (lo.z + hi.z)) / longest);
        }
        if (is_degenerate(p[0], p[1], p[2])) continue;
        mesh.vertices.insert(mesh.vertices.end(), {p[0], p[1], p[2]});
        if (!bunny.normals.empty())
            for (int c = 0; c < 3; ++c) mesh.normals.push_back(bunny.normals[3 * t + std::size_t(c)]);
        mesh.triangle_material.push_back(fur);
    }
    s.meshes.push_back(std::move(mesh));
    const std::size_t side = std::size_t(std::ceil(std::sqrt(double(instances))));
    const float spacing = 1.3f, half = 0.5f * spacing * float(side);
    std::uint32_t state = 12345u;  // a fixed LCG: the same field every time
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    };
    for (std::size_t i = 0; i < instances; ++i) {
        const float x = (float(i % side) + 0.5f) * spacing - half, z = (float(i / side) + 0.5f) * spacing - half;
        const glm::vec3 scale(0.7f + 0.5f * next(), 0.6f + 0.6f * next(), 0.7f + 0.5f * next());
        const glm::mat4 turn = glm::rotate(glm::mat4(1), 2 * glm::pi<float>() * next(), glm::vec3(0, 1, 0));
        const glm::mat4 mirror = glm::scale(glm::mat4(1), glm::vec3(i % 3 == 2 ? -1.0f : 1.0f, 1, 1));
        s.instances.push_back({0, glm::translate(glm::mat4(1), {x, 0, z}) * turn * mirror * glm::scale(glm::mat4(1), scale)});
    }
    const float extent = half + spacing;
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {2 * extent, 1, 2 * extent})), floor);
    s.environment.color = glm::vec3(0.9f, 0.95f, 1.0f);
    s.camera.eye = {-half - 2.0f, 2.5f + 0.08f * half, -half - 2.0f};
    s.camera.target = {0, 0, 0};
    s.camera.vfov_degrees = 50;
    s.camera.width = 640;
    s.camera.height = 360;
    s.name = "bunnies-" + std::to_string(instances);
    return s;
}

Scene night_city_scene(std::size_t lights) {
    if (lights < 1 || lights > 1'000'000)
        throw Error("city:" + std::to_string(lights) + ": the light count must be in [1, 1000000]");
    Scene s;
    const auto ground = s.add_material("street", diffuse({0.3f, 0.3f, 0.32f}));
    const auto wall = s.add_material("building", diffuse({0.6f, 0.55f, 0.5f}));
    // Four kinds of lamp, of one power each: power alone cannot tell a lamp
    // beside the point being shaded from one across the city.
    const std::uint32_t lamp[4] = {
        s.add_material("lamp-warm", emitter(glm::vec3(1.0f, 0.75f, 0.45f) * 12.0f)),
        s.add_material("lamp-white", emitter(glm::vec3(1.0f) * 10.0f)),
        s.add_material("lamp-cool", emitter(glm::vec3(0.6f, 0.8f, 1.0f) * 11.0f)),
        s.add_material("lamp-sodium", emitter(glm::vec3(1.0f, 0.5f, 0.15f) * 14.0f))};
    std::uint32_t state = 424242u;  // a fixed LCG: the same city every time
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    };
    // 8 x 8 blocks of 4 x 4 with streets 2 wide between them, each block one
    // building of its own height.
    constexpr int kBlocks = 8;
    constexpr float kCell = 6.0f, kHalf = 0.5f * kCell * kBlocks;
    s.add_triangles(transformed(make_plane(), shape_transform({0, 0, 0}, {0, 0, 0}, {2 * kHalf + 8, 1, 2 * kHalf + 8})),
                    ground);
    for (int bx = 0; bx < kBlocks; ++bx)
        for (int bz = 0; bz < kBlocks; ++bz) {
            const float h = 1.0f + 5.0f * next();
            const glm::vec3 centre((float(bx) + 0.5f) * kCell - kHalf, 0.5f * h, (float(bz) + 0.5f) * kCell - kHalf);
            s.add_triangles(transformed(make_box(), shape_transform(centre, {0, 0, 0}, {4, h, 4})), wall);
        }
    // Lamps: small squares facing down over the streets (never inside a block).
    for (std::size_t i = 0; i < lights;) {
        const float x = (2 * next() - 1) * kHalf, z = (2 * next() - 1) * kHalf, y = 1.5f + 2.5f * next();
        const float lx = std::fmod(x + kHalf, kCell), lz = std::fmod(z + kHalf, kCell);
        if (lx > 0.9f && lx < 5.1f && lz > 0.9f && lz < 5.1f) continue;
        s.add_triangles(transformed(make_plane(), shape_transform({x, y, z}, {glm::pi<float>(), 0, 0}, {0.25f, 1, 0.25f})),
                        lamp[i % 4]);
        ++i;
    }
    s.camera.eye = {-20.0f, 18.0f, -26.0f};
    s.camera.target = {2.0f, 0.0f, 2.0f};
    s.camera.vfov_degrees = 40;
    s.camera.width = 480;
    s.camera.height = 320;
    s.render.max_depth = 6;
    s.name = "city-" + std::to_string(lights);
    return s;
}

std::vector<std::string> builtin_scene_names() { return {"cornell", "scaling:N", "room:N", "bunnies:N", "city:N"}; }

Scene builtin_scene(const std::string& name) {
    if (name == "cornell") return cornell_thesis_scene();
    // "scaling:1000000" or "scaling:1e6"; the same for "room:".
    for (const auto& [prefix, make] : {std::pair{std::string("scaling:"), &scaling_scene},
                                       std::pair{std::string("room:"), &closed_room_scene},
                                       std::pair{std::string("bunnies:"), &bunnies_scene},
                                       std::pair{std::string("city:"), &night_city_scene}}) {
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string count = name.substr(prefix.size());
        char* end = nullptr;
        const double n = std::strtod(count.c_str(), &end);
        if (count.empty() || *end != '\0' || !(n >= 1) || n != std::floor(n) || n > 1e12)
            throw Error(name + ": expected " + prefix + "N with N a positive whole number (of triangles; of instances for bunnies:, of lamps for city:), e.g. " + prefix +
                        "100000 or " + prefix + "1e6");
        return make(std::size_t(n));
    }
    std::string names;
    for (const auto& n : builtin_scene_names()) names += " " + n;
    throw Error("no built-in scene named '" + name + "' (built-in:" + names + ")");
}

}  // namespace clpath
