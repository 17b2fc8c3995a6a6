#include "bvh/binned_builder.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>

#include "bvh/binning.hpp"
#include "bvh/fork_join.hpp"
#include "bvh/partition.hpp"
#include "bvh/sah_sweep.hpp"
#include "bvh/small_node.hpp"
#include "bvh/build_simd.hpp"

namespace clpath::bvh_build {

namespace {

// Nodes over at least this many triangles are binned and partitioned by all
// threads; smaller subtrees are built whole, one per thread. A size, not a
// share of the threads, so the tree is the same for every thread count.
constexpr std::uint32_t kBigNode = 1u << 14;
// The records a thread bins or scatters at a time in those nodes.
constexpr std::uint32_t kChunk = 1u << 13;

constexpr std::uint32_t kNoParent = ~0u;

// A subtree still to build: records [begin, end), in the scatter array when
// in_tmp. Its box goes in slot side of node parent: one of the top levels'
// (parent_top) or of the subtree's block; the tree's root has none.
struct Range {
    Box4 box, cbox;  // of the triangles' boxes, of their centroids
    std::uint32_t begin, end, parent;
    int depth;  // of this node, root = 1
    std::uint8_t side;
    bool in_tmp, parent_top;
};

// What one thread's subtree wrote: its nodes, numbered from 0 in block, and
// its share of the tree's statistics.
struct Sub {
    BvhNode64* block = nullptr;
    std::uint32_t next = 0;  // nodes so far
    std::size_t leaves = 0;
    double cost = 0;  // SAH, over the root's area
    int max_depth = 0;
};

// A child's slot in its parent: its box, and its node's index (count 0) or
// its first record's complement and record count (a leaf), as two 16-byte
// rows (kernels/shared_structs.h: index and count are the rows' fourth fields).
// The row by arithmetic (slot 1 is 8 floats after slot 0): as a choice
// between lo0 and lo1, a branch on the side missed every few nodes.
void set_slot(BvhNode64& p, int side, const Box4& b, int child, std::uint32_t count) {
    static_assert(offsetof(BvhNode64, hi0) == 16 && offsetof(BvhNode64, lo1) == 32 && offsetof(BvhNode64, hi1) == 48,
                  "slot 1's rows are 8 floats after slot 0's");
    float* row = p.lo0 + 8 * side;
    store3_with(row, b.lo, std::uint32_t(child));
    store3_with(row + 4, b.hi, count);
}

// What a node does: become a leaf, split at an SAH bin boundary, or split at the median.
struct Decision {
    enum Kind { Leaf, Sah, Median } kind = Leaf;
    int axis = 0, bin = 0;
};

class Builder {
public:
    Builder(const BvhBuildOptions& opt, Ref* main, Ref* tmp, float root_area)
        : opt_(opt), main_(main), tmp_(tmp), root_area_(root_area) {}

    // The tree below root into nodes and t (all but refs).
    void build(const Range& root, BvhNodes& nodes, Tree& t) {
        std::vector<Range> tasks, level, next;
        (root.end - root.begin >= kBigNode ? level : tasks).push_back(root);
        while (!level.empty()) {
            big_level(level, next, tasks);
            level.swap(next);
            next.clear();
        }
        // Tasks left to right (the order their statistics are summed in);
        // started largest first, so the last to start is a small one, and
        // their nodes follow the top levels' in that order.
        std::sort(tasks.begin(), tasks.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
        const std::size_t K = tasks.size(), top = top_.size();
        std::vector<std::size_t> order(K);
        for (std::size_t k = 0; k < K; ++k) order[k] = k;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            const std::uint32_t na = tasks[a].end - tasks[a].begin, nb = tasks[b].end - tasks[b].begin;
            return na > nb || (na == nb && a < b);
        });
        // Room for the most nodes the subtrees can have (one fewer than their
        // triangles each); only what they use is written, so the pages past
        // it are never touched.
        std::size_t most = top;
        for (const Range& r : tasks) most += r.end - r.begin - 1;
        nodes.resize(std::max<std::size_t>(most, 1));  // left unwritten, on huge pages (UninitAllocator)
        // Each task builds into a scratch block of its own, hot in its
        // thread's cache, and the blocks are moved to the output in task
        // order as soon as every earlier task's has been (tasks start in
        // that order, so few wait): no block is written to the output
        // before its place there is known, and the output is the same
        // whatever the threads.
        std::vector<Sub> subs(K);
        std::vector<BigArray<BvhNode64>> scratch(K), spare;
        std::vector<char> done(K, 0);
        std::mutex mutex;
        std::size_t moved = 0, at = top;
        auto move_ready = [&] {  // under mutex
            for (; moved < K && done[moved]; ++moved) {
                const std::size_t k = order[moved];
                Sub& s = subs[k];
                if (s.next > 0) {
                    const int offset = int(at);
                    for (std::uint32_t i = 0; i < s.next; ++i) {
                        BvhNode64 x = s.block[i];
                        if (x.child0 >= 0) x.child0 += offset;
                        if (x.child1 >= 0) x.child1 += offset;
                        nodes[at + i] = x;
                    }
                    if (tasks[k].parent != kNoParent) {
                        BvhNode64& p = top_[tasks[k].parent];
                        (tasks[k].side ? p.child1 : p.child0) = offset;
                    }
                    at += s.next;
                }
                spare.push_back(std::move(scratch[k]));
                s.block = nullptr;
            }
        };
        std::atomic<std::size_t> next_task{0};
        const int workers = int(std::min<std::size_t>(std::size_t(opt_.threads), K));
        std::vector<std::unique_ptr<Bins>> worker_bins(std::size_t(std::max(workers, 1)));
        for (auto& b : worker_bins) b = std::make_unique<Bins>();
        fork_join(workers, [&](int w) {
            for (std::size_t i; (i = next_task.fetch_add(1)) < K;) {
                const std::size_t k = order[i];
                {
                    std::lock_guard<std::mutex> lock(mutex);
                    if (!spare.empty()) {
                        scratch[k] = std::move(spare.back());
                        spare.pop_back();
                    }
                }
                // A task has fewer records than kBigNode; a tree of one task, maybe far fewer.
                if (!scratch[k])
                    scratch[k] = big_array<BvhNode64>(K > 1 ? kBigNode - 1 : std::max<std::size_t>(most - top, 1));
                subs[k].block = scratch[k].get();
                subtree(tasks[k], *worker_bins[w], subs[k]);
                std::lock_guard<std::mutex> lock(mutex);
                done[i] = 1;
                move_ready();
            }
        });
        // The sums in a fixed order (top levels, then left to right).
        t.sah_cost = top_cost_;
        t.max_depth = top_depth_;
        t.leaf_count = 0;
        for (const Sub& s : subs) {
            t.sah_cost += s.cost;
            t.leaf_count += s.leaves;
            t.max_depth = std::max(t.max_depth, s.max_depth);
        }
        t.node_count = at;
        std::copy(top_.begin(), top_.end(), nodes.begin());
        if (at == 0) {  // the whole tree is one leaf: the root holds it in slot 0, slot 1 empty
            BvhNode64& n = nodes[0];
            set_slot(n, 0, root.box, ~int(root.begin), root.end - root.begin);
            set_slot(n, 1, root.box, ~0, 0);
            t.node_count = 1;
            t.max_depth = 1;
            t.sah_cost = double(opt_.traversal_cost) + double(root.end - root.begin);
        }
    }

private:
    const BvhBuildOptions& opt_;
    Ref* main_;
    Ref* tmp_;
    const float root_area_;
    std::deque<Bins> part_;  // big_level's bins, one per chunk
    std::vector<BvhNode64> top_;  // the top levels' nodes, level by level
    double top_cost_ = 0;
    int top_depth_ = 0;

    Ref* refs(const Range& r) const { return r.in_tmp ? tmp_ : main_; }

    BvhNode64* parent_of(const Range& r, const Sub& s) {
        if (r.parent == kNoParent) return nullptr;
        return r.parent_top ? &top_[r.parent] : &s.block[r.parent];
    }

    // Its records end in the main array (partitions alternate between the two).
    void leaf(const Range& r, Sub& s) {
        if (r.in_tmp)
            for (std::uint32_t i = r.begin; i < r.end; ++i) main_[i] = tmp_[i];
        const std::uint32_t n = r.end - r.begin;
        ++s.leaves;
        s.cost += double(n) * area(r.box) / root_area_;
        if (BvhNode64* p = parent_of(r, s)) set_slot(*p, r.side, r.box, ~int(r.begin), n);
    }

    // Numbers the node in its subtree's block and links it from its parent.
    std::uint32_t interior(const Range& r, Sub& s) {
        const std::uint32_t index = s.next++;
        s.cost += opt_.traversal_cost * area(r.box) / root_area_;
        s.max_depth = std::max(s.max_depth, r.depth);
        if (BvhNode64* p = parent_of(r, s)) set_slot(*p, r.side, r.box, int(index), 0);
        return index;
    }

    // Never deeper than the traversal stack: when the levels left only just
    // suffice for a balanced tree, split at the median.
    bool force_median(const Range& r) const {
        const std::uint32_t n = r.end - r.begin;
        const int levels_left = CLP_BVH_MAX_DEPTH - r.depth;
        // balanced_needs = ceil(log2(n / max_leaf_size)) + 1: one more than
        // the doublings of the leaf size that reach n, the bit length of
        // ceil(n / max_leaf_size) - 1 (a loop's varying trip count missed
        // a branch every few nodes).
        const std::uint64_t leaves = (std::uint64_t(n) + std::uint64_t(opt_.max_leaf_size) - 1) /
                                     std::uint64_t(opt_.max_leaf_size);
        const int doublings = leaves <= 1 ? 0 : 64 - __builtin_clzll(leaves - 1);
        return 1 + doublings >= levels_left;
    }

    // Leaf, SAH split or median split for node r, whose triangles
    // dense_fill (at least as many as bins) or sparse_fill bins.
    template <class Fill>
    Decision decide(const Range& r, Fill fill, Bins& bins, BinList* lists) const {
        const std::uint32_t n = r.end - r.begin;
        const F4 ext4 = r.cbox.hi - r.cbox.lo;
        const float ext[3] = {lane(ext4, 0), lane(ext4, 1), lane(ext4, 2)};
        const int axis_long = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : (ext[1] >= ext[2] ? 1 : 2);
        Decision d;
        float best_cost = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_bin = 0;
        if (!force_median(r) && ext[axis_long] > 0) {
            fill(bins, lists);
            const int nb = opt_.bins;
            if (lists[0].size == nb && lists[1].size == nb && lists[2].size == nb) {  // every bin: dense
                const bool sweep[3] = {ext[0] > 0, ext[1] > 0, ext[2] > 0};
                sah_sweep_all_bins(bins, nb, sweep, n, best_cost, best_axis, best_bin);
            } else {
                for (int a = 0; a < 3; ++a)
                    if (ext[a] > 0) sah_sweep(bins, a, lists[a], n, best_cost, best_axis, best_bin);
            }
            const float node_area = area(r.box);
            const float split_cost = opt_.traversal_cost + (node_area > 0 ? best_cost / node_area : 0.0f);
            if (n <= std::uint32_t(opt_.max_leaf_size) && (best_axis < 0 || float(n) <= split_cost)) return d;
            if (best_axis >= 0) {
                d.kind = Decision::Sah;
                d.axis = best_axis;
                d.bin = best_bin;
                return d;
            }
        }
        if (n <= std::uint32_t(opt_.max_leaf_size)) return d;
        d.kind = Decision::Median;
        d.axis = axis_long;
        return d;
    }

    // The children's boxes from the bins: exact, as every bin holds the union of its triangles' boxes.
    static void child_boxes(const Bins& bins, const BinList& list, const Decision& d, Box4& left, Box4& right) {
        left = right = Box4{};
        for (int j = 0; j < list.size; ++j) {
            (list.bin[j] <= d.bin ? left : right).grow(bins.box[d.axis][j]);
        }
    }

    // Object median on the axis; ties broken by triangle index, so the split is
    // the same whatever order the records arrive in. Balanced, always progresses.
    std::uint32_t median_split(const Range& r, int axis, Range& left, Range& right) {
        Ref* a = refs(r);
        const std::uint32_t m = r.begin + (r.end - r.begin) / 2;
        std::nth_element(a + r.begin, a + m, a + r.end, [axis](const Ref& x, const Ref& y) {
            const float cx = 0.5f * x.lo[axis] + 0.5f * x.hi[axis], cy = 0.5f * y.lo[axis] + 0.5f * y.hi[axis];
            return cx < cy || (cx == cy && x.prim < y.prim);
        });
        left.box = left.cbox = right.box = right.cbox = Box4{};
        for (std::uint32_t i = r.begin; i < r.end; ++i) {
            const F4 lo = load3(a[i].lo), hi = load3(a[i].hi);
            Range& side = i < m ? left : right;
            side.box.grow(lo, hi);
            side.cbox.grow_point(centroid(lo, hi));
        }
        return m;
    }

    static void set_children(const Range& r, std::uint32_t m, bool in_tmp, std::uint32_t parent, bool parent_top,
                             Range& left, Range& right) {
        left.begin = r.begin;
        left.end = m;
        right.begin = m;
        right.end = r.end;
        left.parent = right.parent = parent;
        left.parent_top = right.parent_top = parent_top;
        left.side = 0;
        right.side = 1;
        left.depth = right.depth = r.depth + 1;
        left.in_tmp = right.in_tmp = in_tmp;
    }

    // The nodes of one level large enough for all threads, together (one
    // fork-join per pass, not per node): parallel binning, then a stable
    // partition scattered into the other array, both by fixed-size chunks
    // (so the result does not depend on the threads). Children this large
    // form the next level, the others become tasks.
    void big_level(const std::vector<Range>& level, std::vector<Range>& next, std::vector<Range>& tasks) {
        const int T = opt_.threads;
        const std::size_t L = level.size();
        const std::size_t first_node = top_.size();  // a large node is never a leaf
        top_.resize(first_node + L);
        // Each node cut into chunks of a fixed size, whatever the thread count,
        // handed out one at a time: a thread that starts late or is preempted
        // (a busy machine) takes fewer, and the bins merge in chunk order.
        struct Chunk {
            std::uint32_t node, begin, end;
        };
        std::vector<Chunk> chunks;
        std::vector<std::size_t> first_chunk(L + 1);
        for (std::size_t i = 0; i < L; ++i) {
            first_chunk[i] = chunks.size();
            for (std::uint32_t b = level[i].begin; b < level[i].end; b += std::min(kChunk, level[i].end - b))
                chunks.push_back({std::uint32_t(i), b, b + std::min(kChunk, level[i].end - b)});
        }
        first_chunk[L] = chunks.size();
        const std::size_t C = chunks.size();
        auto each_chunk = [&](const std::function<void(std::size_t)>& f) {
            std::atomic<std::size_t> next_chunk{0};
            fork_join(int(std::min<std::size_t>(std::size_t(T), C)), [&](int) {
                for (std::size_t c; (c = next_chunk.fetch_add(1)) < C;) f(c);
            });
        };
        std::vector<BinMap> maps;
        maps.reserve(L);
        for (const Range& r : level) maps.emplace_back(r.cbox, opt_.bins);
        // Per chunk, reused from level to level: a Bins is 27 KB, and
        // constructing one per chunk per level wrote megabytes for nothing.
        if (part_.size() < C) part_.resize(C);  // a deque: the existing ones stay put
        std::deque<Bins>& part = part_;
        each_chunk([&](std::size_t c) {
            const Chunk& ch = chunks[c];
            bin_refs(refs(level[ch.node]), ch.begin, ch.end, maps[ch.node], part[c]);
        });
        struct Split {
            Decision d;
            Range left{}, right{};
        };
        std::vector<Split> split(L);
        std::vector<std::uint32_t> left_at(C), right_at(C);  // per chunk: where its records go
        auto total_bins = std::make_unique<Bins>();
        Bins& total = *total_bins;
        BinList lists[3];
        for (std::size_t i = 0; i < L; ++i) {
            const Range& r = level[i];
            Split& sp = split[i];
            sp.d = decide(
                r,
                [&](Bins& bins, BinList* lists) {
                    bins.clear(opt_.bins);
                    for (std::size_t c = first_chunk[i]; c < first_chunk[i + 1]; ++c) bins.merge(part[c], opt_.bins);
                    for (int a = 0; a < 3; ++a) list_all(opt_.bins, lists[a]);
                },
                total, lists);
            if (sp.d.kind != Decision::Sah) continue;
            // Each chunk's left count is known from its bins: scatter without a counting pass.
            child_boxes(total, lists[sp.d.axis], sp.d, sp.left.box, sp.right.box);
            std::uint32_t left_total = 0;
            for (int k = 0; k <= sp.d.bin; ++k) left_total += total.count[sp.d.axis][k];
            std::uint32_t l_at = r.begin, r_at = r.begin + left_total;
            for (std::size_t c = first_chunk[i]; c < first_chunk[i + 1]; ++c) {
                std::uint32_t l = 0;
                for (int k = 0; k <= sp.d.bin; ++k) l += part[c].count[sp.d.axis][k];
                left_at[c] = l_at;
                right_at[c] = r_at;
                l_at += l;
                r_at += chunks[c].end - chunks[c].begin - l;
            }
        }
        std::vector<Box4> lc(C), rc(C);
        each_chunk([&](std::size_t c) {
            const Chunk& ch = chunks[c];
            const Split& sp = split[ch.node];
            if (sp.d.kind != Decision::Sah) return;
            const Range& r = level[ch.node];
            const Ref* src = refs(r);
            Ref* dst = r.in_tmp ? main_ : tmp_;
            Box4 lcb, rcb;
            scatter_refs_stable(src, dst, ch.begin, ch.end, left_at[c], right_at[c], maps[ch.node], sp.d.axis,
                                sp.d.bin, lcb, rcb);
            lc[c] = lcb;
            rc[c] = rcb;
        });
        for (std::size_t i = 0; i < L; ++i) {
            const Range& r = level[i];
            Split& sp = split[i];
            std::uint32_t m;
            bool in_tmp = r.in_tmp;
            if (sp.d.kind == Decision::Sah) {
                m = right_at[first_chunk[i]];
                in_tmp = !r.in_tmp;
                for (std::size_t c = first_chunk[i]; c < first_chunk[i + 1]; ++c) {
                    sp.left.cbox.grow(lc[c]);
                    sp.right.cbox.grow(rc[c]);
                }
            } else {
                m = median_split(r, sp.d.axis, sp.left, sp.right);  // a big node never becomes a leaf
            }
            const std::uint32_t index = std::uint32_t(first_node + i);
            top_cost_ += opt_.traversal_cost * area(r.box) / root_area_;
            top_depth_ = std::max(top_depth_, r.depth);
            if (r.parent != kNoParent) set_slot(top_[r.parent], r.side, r.box, int(index), 0);
            set_children(r, m, in_tmp, index, true, sp.left, sp.right);
            for (const Range* c : {&sp.left, &sp.right}) (c->end - c->begin >= kBigNode ? next : tasks).push_back(*c);
        }
    }

    // A node over two records (the commonest kind), decided and split
    // without bins, sweeps or a partition pass, into the tree decide() and
    // partition_refs give: its one possible split puts each record in a leaf
    // of its own. Every axis that tells the two apart prices it the same
    // (area + area, a sum that does not depend on the order), so the sweep's
    // first-of-equal-costs rule picks the first such axis, and the record in
    // its lower bin goes left. False (nothing done) where leaves must hold
    // single records: decide() may split at the median then.
    bool pair(const Range& r, Sub& s) {
        if (opt_.max_leaf_size < 2) return false;
        const Ref* a = refs(r);
        const Ref p = a[r.begin], q = a[r.begin + 1];
        const F4 plo = load3(p.lo), phi = load3(p.hi), qlo = load3(q.lo), qhi = load3(q.hi);
        int axis = -1, kp[3], kq[3];
        if (!force_median(r)) {
            const BinMap map(r.cbox, opt_.bins);
            bin_index3((centroid(plo, phi) - map.lo) * map.scale, map.top, kp[0], kp[1], kp[2]);
            bin_index3((centroid(qlo, qhi) - map.lo) * map.scale, map.top, kq[0], kq[1], kq[2]);
            const F4 ext = r.cbox.hi - r.cbox.lo;
            for (int ax = 0; ax < 3 && axis < 0; ++ax)
                if (lane(ext, ax) > 0 && kp[ax] != kq[ax]) axis = ax;
        }
        if (axis >= 0) {
            const float cost = area_of_extent(phi - plo) + area_of_extent(qhi - qlo);
            const float node_area = area(r.box);
            const float split_cost = opt_.traversal_cost + (node_area > 0 ? cost / node_area : 0.0f);
            if (!(cost < std::numeric_limits<float>::infinity()) || 2.0f <= split_cost) axis = -1;
        }
        if (axis < 0) {
            leaf(r, s);
            return true;
        }
        const bool swap = kq[axis] < kp[axis];
        main_[r.begin] = swap ? q : p;
        main_[r.begin + 1] = swap ? p : q;
        BvhNode64& n = s.block[interior(r, s)];
        Box4 lb, rb;
        lb.lo = swap ? qlo : plo;
        lb.hi = swap ? qhi : phi;
        rb.lo = swap ? plo : qlo;
        rb.hi = swap ? phi : qhi;
        set_slot(n, 0, lb, ~int(r.begin), 1);
        set_slot(n, 1, rb, ~int(r.begin + 1), 1);
        s.leaves += 2;
        s.cost += double(area(lb)) / root_area_;
        s.cost += double(area(rb)) / root_area_;
        return true;
    }

    // A whole subtree on one thread: depth first, each SAH partition scattered
    // into the other array (a median split stays in place), its nodes into out.
    // Counted in a copy on this thread's stack, stored once: the tasks' Subs
    // share cache lines, and another thread's task may be next to this one.
    void subtree(const Range& root, Bins& bins, Sub& out) {
        Sub s = out;
        build_subtree(root, bins, s);
        out = s;
    }

    void build_subtree(const Range& root, Bins& bins, Sub& s) {
        Range stack[2 * CLP_BVH_MAX_DEPTH + 4];
        BinList lists[3];
        int sp = 0;
        stack[sp++] = root;
        const std::uint32_t dense_from = std::uint32_t(opt_.bins);
        // A node's left child goes on in r and its right child is built in
        // its stack slot: copying a just-built child through the stack whole
        // stalled every node, as its fields were stored one by one and read
        // back 16 bytes at a time (a store cannot be forwarded to a wider load).
        while (sp > 0) {
            Range r = stack[--sp];  // a right child, stored long ago
            for (;;) {
                Ref* a = refs(r);
                const std::uint32_t n = r.end - r.begin;
                if (n == 1) {  // a point's centroid bounds: decide() would find no split either
                    leaf(r, s);
                    break;
                }
                if (n == 2 && pair(r, s)) break;
                Range left{};
                if (n <= kSmallNodeMax && !force_median(r)) {
                    const SmallSplit ss = small_split(a, r.in_tmp ? main_ : tmp_, r.begin, r.end, r.box, r.cbox,
                                                      opt_.bins, opt_.max_leaf_size, opt_.traversal_cost);
                    if (ss.kind == SmallSplit::Leaf) {
                        leaf(r, s);
                        break;
                    }
                    if (ss.kind == SmallSplit::Split) {
                        Range& right = stack[sp++];
                        right = Range{};
                        left.box = ss.left_box;
                        left.cbox = ss.left_cbox;
                        right.box = ss.right_box;
                        right.cbox = ss.right_cbox;
                        set_children(r, ss.mid, !r.in_tmp, interior(r, s), false, left, right);
                        continue_left(r, left);
                        continue;
                    }
                }
                const BinMap map(r.cbox, opt_.bins);
                const Decision d = decide(
                    r,
                    [&](Bins& b, BinList* l) {
                        if (n == 2) {
                            bin_refs_pair(a, r.begin, map, b, l);
                        } else if (n < dense_from) {
                            bin_refs_sparse(a, r.begin, r.end, map, b, l);
                        } else {
                            bin_refs(a, r.begin, r.end, map, b);
                            for (int ax = 0; ax < 3; ++ax) list_all(opt_.bins, l[ax]);
                        }
                    },
                    bins, lists);
                if (d.kind == Decision::Leaf) {
                    leaf(r, s);
                    break;
                }
                Range& right = stack[sp++];
                right = Range{};
                std::uint32_t m = r.begin;
                bool in_tmp = r.in_tmp;
                if (d.kind == Decision::Sah) {
                    // Into the other array: the children live there from now on.
                    m = partition_refs(a, r.in_tmp ? main_ : tmp_, r.begin, r.end, map, d.axis, d.bin, left.cbox,
                                       right.cbox);
                    in_tmp = !r.in_tmp;
                    child_boxes(bins, lists[d.axis], d, left.box, right.box);
                } else {
                    m = median_split(r, d.axis, left, right);
                }
                set_children(r, m, in_tmp, interior(r, s), false, left, right);
                continue_left(r, left);
            }
        }
    }

    // The subtree loop goes on with r's left child, field by field (see subtree()).
    static void continue_left(Range& r, const Range& left) {
        r.box = left.box;
        r.cbox = left.cbox;
        r.end = left.end;
        r.parent = left.parent;
        r.parent_top = false;
        r.side = 0;
        r.depth = left.depth;
        r.in_tmp = left.in_tmp;
    }
};

}  // namespace

Tree build_tree(const std::vector<glm::vec3>& vertices, const BvhBuildOptions& opt, BvhNodes& nodes,
                Ref* scatter) {
    const std::size_t n = vertices.size() / 3;
    Tree tree;
    tree.ref_count = n;
    tree.refs = big_array<Ref>(n);  // left uninitialised: the threads below touch it first

    const RootBounds rb = make_records(vertices, opt.threads, tree.refs.get());
    Range root{};
    root.box = rb.box;
    root.cbox = rb.cbox;
    root.begin = 0;
    root.end = std::uint32_t(n);
    root.parent = kNoParent;
    root.depth = 1;
    root.side = 0;
    root.in_tmp = root.parent_top = false;
    Builder builder(opt, tree.refs.get(), scatter, std::max(area(root.box), 1e-30f));
    builder.build(root, nodes, tree);
    return tree;
}

}  // namespace clpath::bvh_build
