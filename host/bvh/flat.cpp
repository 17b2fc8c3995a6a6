#include "bvh/flat.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <string>

#include "util/error.hpp"

namespace clpath {
namespace {

struct ObjectBox {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    std::uint32_t first = 0, count = 0;
    float area() const {
        const glm::vec3 e = glm::max(hi - lo, glm::vec3(0));
        return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

void set_slot(BvhNode64& n, int slot, const ObjectBox& b) {
    float* lo = slot ? n.lo1 : n.lo0;
    float* hi = slot ? n.hi1 : n.hi0;
    for (int a = 0; a < 3; ++a) {
        lo[a] = b.lo[a];
        hi[a] = b.hi[a];
    }
    (slot ? n.child1 : n.child0) = ~int(b.first);
    (slot ? n.count1 : n.count0) = b.count;
}

}  // namespace

Bvh build_flat(const std::vector<glm::vec3>& vertices, const std::vector<std::uint32_t>& triangle_object,
               float traversal_cost) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = vertices.size() / 3;
    if (n == 0) throw Error("flat structure: no triangles");
    if (n > 0x7fffffffu) throw Error("flat structure: " + std::to_string(n) + " triangles; at most 2^31 - 1 fit the node layout");
    if (triangle_object.size() != n)
        throw Error("flat structure: " + std::to_string(triangle_object.size()) + " object ids for " +
                    std::to_string(n) + " triangles");
    // Objects in order of first appearance; triangles grouped by object, in
    // scene order within one (a counting sort, so it is stable and O(n)).
    std::map<std::uint32_t, std::uint32_t> slot_of;
    std::vector<std::uint32_t> count;
    std::vector<std::uint32_t> obj(n);
    std::uint32_t prev_id = 0, prev_slot = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (i == 0 || triangle_object[i] != prev_id) {  // objects come in runs: one lookup per run
            auto [it, fresh] = slot_of.try_emplace(triangle_object[i], std::uint32_t(count.size()));
            if (fresh) count.push_back(0);
            prev_id = triangle_object[i];
            prev_slot = it->second;
        }
        obj[i] = prev_slot;
        ++count[prev_slot];
    }
    std::vector<ObjectBox> boxes(count.size());
    std::uint32_t first = 0;
    for (std::size_t o = 0; o < boxes.size(); ++o) {
        boxes[o].first = first;
        first += count[o];
    }
    Bvh flat;
    flat.triangles.resize(n);
    std::vector<std::uint32_t> next(boxes.size());
    for (std::size_t o = 0; o < boxes.size(); ++o) next[o] = boxes[o].first;
    for (std::size_t i = 0; i < n; ++i) {
        ObjectBox& b = boxes[obj[i]];
        TriVerts& t = flat.triangles[next[obj[i]]++];
        for (int a = 0; a < 3; ++a) {
            t.v0[a] = vertices[3 * i][a];
            t.v1[a] = vertices[3 * i + 1][a];
            t.v2[a] = vertices[3 * i + 2][a];
        }
        for (int k = 0; k < 3; ++k) {
            b.lo = glm::min(b.lo, vertices[3 * i + k]);
            b.hi = glm::max(b.hi, vertices[3 * i + k]);
        }
        ++b.count;
        t.prim = std::uint32_t(i);
        t.light = CLP_NO_LIGHT;  // the renderer marks emitters
        t.pad2 = 0;
    }
    // Two objects per record, then a terminating slot (child >= 0).
    flat.nodes.assign(boxes.size() / 2 + 1, BvhNode64{});
    for (std::size_t o = 0; o < boxes.size(); ++o) set_slot(flat.nodes[o / 2], int(o % 2), boxes[o]);
    BvhNode64& last = flat.nodes.back();
    if (boxes.size() % 2) {
        last.child1 = 0;
        last.count1 = 0;
    } else {
        last.child0 = last.child1 = 0;
    }

    ObjectBox root;
    for (const auto& b : boxes) {
        root.lo = glm::min(root.lo, b.lo);
        root.hi = glm::max(root.hi, b.hi);
    }
    const double root_area = std::max(double(root.area()), 1e-30);
    double cost = traversal_cost * double(flat.nodes.size());
    for (const auto& b : boxes) cost += double(b.count) * b.area() / root_area;
    BvhStats& st = flat.stats;
    st.node_count = flat.nodes.size();
    st.leaf_count = boxes.size();
    st.max_depth = 1;
    st.sah_cost = cost;
    st.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return flat;
}

void check_flat(const Bvh& flat, std::size_t triangle_count) {
    auto fail = [](const std::string& what) { throw std::logic_error("flat structure invariant broken: " + what); };
    if (flat.triangles.size() != triangle_count) fail("triangle count differs from the scene's");
    std::vector<int> seen(triangle_count, 0);
    bool ended = false;
    std::size_t next_first = 0;
    for (std::size_t r = 0; r < flat.nodes.size() && !ended; ++r) {
        const BvhNode64& n = flat.nodes[r];
        for (int s = 0; s < 2 && !ended; ++s) {
            const int child = s ? n.child1 : n.child0;
            if (child >= 0) {
                ended = true;
                break;
            }
            const float* lo = s ? n.lo1 : n.lo0;
            const float* hi = s ? n.hi1 : n.hi0;
            const std::size_t first = std::size_t(~child), count = s ? n.count1 : n.count0;
            if (first != next_first || first + count > triangle_count) fail("object ranges do not tile the triangles");
            next_first = first + count;
            for (std::size_t i = first; i < first + count; ++i) {
                const TriVerts& t = flat.triangles[i];
                for (const float* v : {t.v0, t.v1, t.v2})
                    for (int a = 0; a < 3; ++a)
                        if (!(v[a] >= lo[a] && v[a] <= hi[a]))
                            fail("triangle " + std::to_string(t.prim) + " sticks out of its object's box");
                if (t.prim >= triangle_count || seen[t.prim]++) fail("triangle index repeated or out of range");
            }
        }
    }
    if (!ended) fail("the list has no terminating slot");
    if (next_first != triangle_count) fail("not every triangle is in an object");
}

}  // namespace clpath
