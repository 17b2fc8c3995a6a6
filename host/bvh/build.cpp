#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>
#include <stdexcept>
#include <thread>

#include "bvh/bvh.hpp"

namespace clpath {
namespace {

struct Box {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x; }
    float area() const {
        if (empty()) return 0;
        const glm::vec3 e = hi - lo;
        return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

// A node of the binary tree, before flattening: a leaf when count > 0.
struct BinNode {
    Box box;
    int left = -1, right = -1;  // indices in the same subtree vector
    std::uint32_t first = 0, count = 0;
};

struct Builder {
    const std::vector<Box>& tri_box;
    const std::vector<glm::vec3>& centroid;
    std::vector<std::uint32_t>& index;
    BvhBuildOptions opt;
    int spawn_budget;  // subtrees that may still get their own thread

    static constexpr std::uint32_t kParallelSplit = 8192;   // subtrees larger than this get a task
    static constexpr std::uint32_t kParallelBinning = 65536;

    struct Bins {
        std::vector<Box> box;
        std::vector<std::uint32_t> count;
    };

    // Wald (2007): bin centroids into `bins` equal slabs per axis, then sweep
    // the bin boundaries; cost O(n) per node instead of a sort.
    void bin_range(std::uint32_t begin, std::uint32_t end, const Box& cbox, std::vector<Bins>& out) const {
        const int B = opt.bins;
        for (int a = 0; a < 3; ++a) {
            out[a].box.assign(B, Box{});
            out[a].count.assign(B, 0);
        }
        const glm::vec3 extent = cbox.hi - cbox.lo;
        const glm::vec3 scale = glm::vec3(float(B)) / glm::max(extent, glm::vec3(1e-30f));
        for (std::uint32_t i = begin; i < end; ++i) {
            const std::uint32_t t = index[i];
            for (int a = 0; a < 3; ++a) {
                const int b = std::min(B - 1, int((centroid[t][a] - cbox.lo[a]) * scale[a]));
                out[a].box[b].grow(tri_box[t]);
                ++out[a].count[b];
            }
        }
    }

    std::vector<Bins> bin(std::uint32_t begin, std::uint32_t end, const Box& cbox) const {
        std::vector<Bins> bins(3);
        const std::uint32_t n = end - begin;
        const int threads = std::max(1, opt.threads);
        if (n < kParallelBinning || threads == 1) {
            bin_range(begin, end, cbox, bins);
            return bins;
        }
        // Chunks binned in parallel, merged in chunk order (min/max and sums: order-independent).
        std::vector<std::vector<Bins>> part(threads, std::vector<Bins>(3));
        std::vector<std::future<void>> jobs;
        for (int t = 0; t < threads; ++t) {
            const std::uint32_t b = begin + std::uint32_t(std::uint64_t(n) * t / threads);
            const std::uint32_t e = begin + std::uint32_t(std::uint64_t(n) * (t + 1) / threads);
            jobs.push_back(std::async(std::launch::async, [&, b, e, t] { bin_range(b, e, cbox, part[t]); }));
        }
        for (auto& j : jobs) j.get();
        bins = part[0];
        for (int t = 1; t < threads; ++t)
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < opt.bins; ++k) {
                    bins[a].box[k].grow(part[t][a].box[k]);
                    bins[a].count[k] += part[t][a].count[k];
                }
        return bins;
    }

    // Splits [begin, end) and returns the split point, or begin for "make a leaf".
    std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Box& box, int depth) {
        const std::uint32_t n = end - begin;
        Box cbox;
        for (std::uint32_t i = begin; i < end; ++i) cbox.grow(centroid[index[i]]);
        const int axis_long = [&] {
            const glm::vec3 e = cbox.hi - cbox.lo;
            return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        }();
        // Never deeper than the traversal stack: when the remaining levels only
        // just suffice for a balanced tree, split at the median.
        const int levels_left = CLP_BVH_MAX_DEPTH - depth;
        const int balanced_needs = int(std::ceil(std::log2(double(n) / opt.max_leaf_size))) + 1;
        const bool force_median = balanced_needs >= levels_left;

        if (!force_median && cbox.hi[axis_long] > cbox.lo[axis_long]) {
            const auto bins = bin(begin, end, cbox);
            const int B = opt.bins;
            float best_cost = std::numeric_limits<float>::infinity();
            int best_axis = -1, best_bin = 0;
            std::vector<float> right_cost(B);
            for (int a = 0; a < 3; ++a) {
                if (!(cbox.hi[a] > cbox.lo[a])) continue;
                Box acc;
                std::uint32_t cnt = 0;
                for (int k = B - 1; k > 0; --k) {  // right side areas, swept from the right
                    acc.grow(bins[a].box[k]);
                    cnt += bins[a].count[k];
                    right_cost[k] = acc.area() * float(cnt);
                }
                acc = Box{};
                cnt = 0;
                for (int k = 0; k < B - 1; ++k) {
                    acc.grow(bins[a].box[k]);
                    cnt += bins[a].count[k];
                    if (cnt == 0 || cnt == n) continue;
                    const float c = acc.area() * float(cnt) + right_cost[k + 1];
                    if (c < best_cost) {
                        best_cost = c;
                        best_axis = a;
                        best_bin = k;
                    }
                }
            }
            const float area = box.area();
            const float split_cost = opt.traversal_cost + (area > 0 ? best_cost / area : 0.0f);
            if (n <= std::uint32_t(opt.max_leaf_size) && (best_axis < 0 || float(n) <= split_cost)) return begin;
            if (best_axis >= 0) {
                const float scale = float(B) / (cbox.hi[best_axis] - cbox.lo[best_axis]);
                const float lo = cbox.lo[best_axis];
                auto mid = std::partition(index.begin() + begin, index.begin() + end, [&](std::uint32_t t) {
                    return std::min(B - 1, int((centroid[t][best_axis] - lo) * scale)) <= best_bin;
                });
                const auto m = std::uint32_t(mid - index.begin());
                if (m > begin && m < end) return m;
            }
        }
        if (n <= std::uint32_t(opt.max_leaf_size)) return begin;
        // Object median on the longest centroid axis; ties broken by triangle
        // index so the result is deterministic. Always balanced, always progresses.
        const std::uint32_t m = begin + n / 2;
        std::nth_element(index.begin() + begin, index.begin() + m, index.begin() + end,
                         [&](std::uint32_t x, std::uint32_t y) {
                             const float cx = centroid[x][axis_long], cy = centroid[y][axis_long];
                             return cx < cy || (cx == cy && x < y);
                         });
        return m;
    }

    // Builds the subtree of [begin, end) into out (preorder), returns its root index.
    int build(std::uint32_t begin, std::uint32_t end, int depth, std::vector<BinNode>& out) {
        Box box;
        for (std::uint32_t i = begin; i < end; ++i) box.grow(tri_box[index[i]]);
        const int me = int(out.size());
        out.push_back(BinNode{box, -1, -1, begin, 0});
        const std::uint32_t m = split(begin, end, box, depth);
        if (m == begin) {
            out[me].count = end - begin;
            return me;
        }
        // A large right subtree goes to its own thread (into its own vector, so
        // the final layout does not depend on which thread finishes first).
        std::vector<BinNode> right_nodes;
        std::future<void> right_job;
        const bool spawn = end - m > kParallelSplit && spawn_budget > 0;
        if (spawn) {
            --spawn_budget;
            right_job = std::async(std::launch::async, [this, m, end, depth, &right_nodes] {
                build(m, end, depth + 1, right_nodes);
            });
        }
        out[me].left = build(begin, m, depth + 1, out);
        if (spawn) {
            right_job.get();
            const int offset = int(out.size());
            for (auto n : right_nodes) {
                if (n.left >= 0) n.left += offset;
                if (n.right >= 0) n.right += offset;
                out.push_back(n);
            }
            out[me].right = offset;
        } else {
            out[me].right = build(m, end, depth + 1, out);
        }
        return me;
    }
};

void store_box(float* lo, float* hi, const Box& b) {
    for (int a = 0; a < 3; ++a) {
        lo[a] = b.lo[a];
        hi[a] = b.hi[a];
    }
}

// Flattens the binary tree: one BvhNode per interior node, leaves inline in
// their parent's slot (Aila & Laine 2009 layout).
void flatten(const std::vector<BinNode>& bin, Bvh& bvh, float traversal_cost) {
    const float root_area = std::max(bin[0].box.area(), 1e-30f);
    auto set_slot = [&](BvhNode& node, int slot, const BinNode& c, int child_index) {
        float* lo = slot == 0 ? node.lo0 : node.lo1;
        float* hi = slot == 0 ? node.hi0 : node.hi1;
        store_box(lo, hi, c.box);
        const int child = c.count ? ~int(c.first) : child_index;
        (slot == 0 ? node.child0 : node.child1) = child;
        (slot == 0 ? node.count0 : node.count1) = c.count;
    };
    BvhStats& st = bvh.stats;
    if (bin[0].count) {  // the whole tree is one leaf
        BvhNode root{};
        set_slot(root, 0, bin[0], 0);
        set_slot(root, 1, bin[0], 0);
        root.child1 = ~0;
        root.count1 = 0;
        bvh.nodes.push_back(root);
        st.leaf_count = 1;
        st.max_depth = 1;
        st.sah_cost = traversal_cost + bin[0].count;
        return;
    }
    // Depth-first, explicit stack: (binary node, its BvhNode index, depth).
    struct Item {
        int bin, node, depth;
    };
    std::vector<Item> stack{{0, 0, 1}};
    bvh.nodes.emplace_back();
    double cost = 0;
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const BinNode& b = bin[it.bin];
        cost += traversal_cost * b.box.area() / root_area;
        st.max_depth = std::max(st.max_depth, it.depth);
        const int kids[2] = {b.left, b.right};
        for (int s = 0; s < 2; ++s) {
            const BinNode& c = bin[kids[s]];
            int index = 0;
            if (c.count) {
                ++st.leaf_count;
                cost += double(c.count) * c.box.area() / root_area;
            } else {
                index = int(bvh.nodes.size());
                bvh.nodes.emplace_back();
                stack.push_back({kids[s], index, it.depth + 1});
            }
            set_slot(bvh.nodes[it.node], s, c, index);
        }
    }
    st.sah_cost = cost;
}

}  // namespace

Bvh build_bvh(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = vertices.size() / 3;
    if (n == 0) throw std::invalid_argument("cannot build a BVH over no triangles");
    if (n > 0x7fffffffu) throw std::invalid_argument("more than 2^31 triangles");
    BvhBuildOptions opt = options;
    if (opt.threads <= 0) opt.threads = int(std::max(1u, std::thread::hardware_concurrency()));
    opt.bins = std::clamp(opt.bins, 2, 256);
    opt.max_leaf_size = std::clamp(opt.max_leaf_size, 1, 64);

    std::vector<Box> tri_box(n);
    std::vector<glm::vec3> centroid(n);
    std::vector<std::uint32_t> index(n);
    for (std::size_t i = 0; i < n; ++i) {
        Box b;
        for (int k = 0; k < 3; ++k) b.grow(vertices[3 * i + k]);
        tri_box[i] = b;
        centroid[i] = 0.5f * (b.lo + b.hi);
        index[i] = std::uint32_t(i);
    }
    Builder builder{tri_box, centroid, index, opt, opt.threads * 2};
    std::vector<BinNode> bin;
    bin.reserve(2 * n / std::max(1, opt.max_leaf_size) + 1);
    builder.build(0, std::uint32_t(n), 1, bin);

    Bvh bvh;
    flatten(bin, bvh, opt.traversal_cost);
    bvh.triangles.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        TriVerts& t = bvh.triangles[i];
        const std::size_t s = index[i];
        for (int a = 0; a < 3; ++a) {
            t.v0[a] = vertices[3 * s][a];
            t.v1[a] = vertices[3 * s + 1][a];
            t.v2[a] = vertices[3 * s + 2][a];
        }
        t.prim = std::uint32_t(s);
        t.light = CLP_NO_LIGHT;  // the renderer marks emitters
        t.pad2 = 0;
    }
    bvh.stats.node_count = bvh.nodes.size();
    bvh.stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return bvh;
}

std::string describe(const BvhStats& s) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "BVH: %zu nodes, %zu leaves, depth %d, SAH cost %.2f, built in %.1f ms",
                  s.node_count, s.leaf_count, s.max_depth, s.sah_cost, s.build_ms);
    return buf;
}

void check_bvh(const Bvh& bvh, std::size_t triangle_count) {
    auto fail = [](const std::string& what) { throw std::logic_error("BVH invariant broken: " + what); };
    if (bvh.nodes.empty()) fail("no root");
    if (bvh.triangles.size() != triangle_count) fail("triangle count differs from the scene's");
    std::vector<int> seen_tri(triangle_count, 0), seen_node(bvh.nodes.size(), 0);
    auto contains = [](const float* lo, const float* hi, const float* p) {
        for (int a = 0; a < 3; ++a)
            if (!(p[a] >= lo[a] && p[a] <= hi[a])) return false;
        return true;
    };
    auto contains_box = [](const float* lo, const float* hi, const float* clo, const float* chi) {
        for (int a = 0; a < 3; ++a)
            if (!(clo[a] >= lo[a] && chi[a] <= hi[a])) return false;
        return true;
    };
    struct Item {
        int node, depth;
    };
    std::vector<Item> stack{{0, 1}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        if (it.depth > CLP_BVH_MAX_DEPTH) fail("depth " + std::to_string(it.depth) + " exceeds the traversal stack");
        if (seen_node[it.node]++) fail("node " + std::to_string(it.node) + " reached twice");
        const BvhNode& n = bvh.nodes[it.node];
        for (int s = 0; s < 2; ++s) {
            const float* lo = s ? n.lo1 : n.lo0;
            const float* hi = s ? n.hi1 : n.hi0;
            const int child = s ? n.child1 : n.child0;
            const std::uint32_t count = s ? n.count1 : n.count0;
            if (child >= 0) {
                if (std::size_t(child) >= bvh.nodes.size()) fail("child index out of range");
                const BvhNode& c = bvh.nodes[child];
                if (!contains_box(lo, hi, c.lo0, c.hi0) || !contains_box(lo, hi, c.lo1, c.hi1))
                    fail("node " + std::to_string(child) + "'s box is not inside its parent's slot");
                stack.push_back({child, it.depth + 1});
                continue;
            }
            const std::size_t first = std::size_t(~child);
            if (first + count > bvh.triangles.size()) fail("leaf range out of range");
            for (std::size_t i = first; i < first + count; ++i) {
                const TriVerts& t = bvh.triangles[i];
                if (!contains(lo, hi, t.v0) || !contains(lo, hi, t.v1) || !contains(lo, hi, t.v2))
                    fail("triangle " + std::to_string(t.prim) + " sticks out of its leaf box");
                if (t.prim >= triangle_count) fail("triangle index out of range");
                if (seen_tri[t.prim]++) fail("triangle " + std::to_string(t.prim) + " referenced twice");
            }
        }
    }
    for (std::size_t i = 0; i < triangle_count; ++i)
        if (!seen_tri[i]) fail("triangle " + std::to_string(i) + " not referenced");
    for (std::size_t i = 0; i < seen_node.size(); ++i)
        if (!seen_node[i]) fail("node " + std::to_string(i) + " unreachable");
}

}  // namespace clpath
