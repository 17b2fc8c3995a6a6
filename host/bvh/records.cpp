#include "bvh/records.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "bvh/binning.hpp"
#include "bvh/fork_join.hpp"
#include "util/error.hpp"

namespace clpath::bvh_build {

namespace {
// Triangles per job, handed out one at a time: a thread that starts late or
// is preempted takes fewer, and the bounds merge in chunk order.
constexpr std::size_t kChunk = 1u << 13;
}  // namespace

RootBounds make_records(const std::vector<glm::vec3>& vertices, int threads, Ref* refs) {
    const std::size_t n = vertices.size() / 3;
    const std::size_t C = (n + kChunk - 1) / kChunk;
    std::vector<Box4> box(C), cbox(C);
    std::vector<std::size_t> bad(C, n);
    std::atomic<std::size_t> next_chunk{0};
    fork_join(int(std::min<std::size_t>(std::size_t(std::max(threads, 1)), C)), [&](int) {
        for (std::size_t k; (k = next_chunk.fetch_add(1)) < C;) {
            Box4 b, c;
            for (std::size_t i = k * kChunk; i < std::min(n, (k + 1) * kChunk); ++i) {
                const glm::vec3 &p = vertices[3 * i], &q = vertices[3 * i + 1], &s = vertices[3 * i + 2];
                Ref& r = refs[i];
                bool finite = true;
                float l[3], h[3];
                for (int a = 0; a < 3; ++a) {
                    l[a] = r.lo[a] = std::min({p[a], q[a], s[a]});
                    h[a] = r.hi[a] = std::max({p[a], q[a], s[a]});
                    finite = finite && std::isfinite(p[a]) && std::isfinite(q[a]) && std::isfinite(s[a]);
                }
                if (!finite && bad[k] == n) bad[k] = i;
                r.prim = std::uint32_t(i);
                r.pad = 0;
                // From registers: reading the record back as 16 bytes just
                // after its 4-byte prim and pad were stored stalled every
                // record (a store cannot be forwarded to a wider load).
                const F4 lo = set4(l[0], l[1], l[2], 0.0f), hi = set4(h[0], h[1], h[2], 0.0f);
                b.grow(lo, hi);
                c.grow_point(centroid(lo, hi));
            }
            box[k] = b;
            cbox[k] = c;
        }
    });
    for (std::size_t i : bad)  // chunks in order: the first one found is the lowest index
        if (i < n) throw Error("BVH build: triangle " + std::to_string(i) + " has a non-finite vertex coordinate");
    RootBounds root;
    for (std::size_t k = 0; k < C; ++k) {
        root.box.grow(box[k]);
        root.cbox.grow(cbox[k]);
    }
    return root;
}

}  // namespace clpath::bvh_build
