#include "bench/embree_baseline.hpp"

#include "util/error.hpp"

#if CLPATH_WITH_EMBREE
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <system_error>
#include <thread>

#include <embree3/rtcore.h>

#include "bench/embree_scene.hpp"
#endif

namespace clpath {

#if !CLPATH_WITH_EMBREE

bool embree_built_in() { return false; }

std::unique_ptr<EmbreeBaseline> make_embree_baseline(const std::vector<glm::vec3>&, EmbreeMode, int) { return nullptr; }

std::unique_ptr<EmbreeBaseline> make_embree_instanced_baseline(const std::vector<const std::vector<glm::vec3>*>&,
                                                               const std::vector<std::pair<std::uint32_t, glm::mat4>>&,
                                                               EmbreeMode, int) {
    return nullptr;
}

#else

bool embree_built_in() { return true; }

namespace {

// Rays handed to Embree per call (rtcIntersect1M / rtcOccluded1M: a stream of
// single rays, which Embree may reorder into packets internally).
constexpr std::size_t kBlock = 256;

void init_ray(RTCRay& r, const BatchRay& b) {
    init_embree_ray(r, {b.o[0], b.o[1], b.o[2]}, {b.d[0], b.d[1], b.d[2]}, b.tmax);
}

class Baseline final : public EmbreeBaseline {
public:
    Baseline(const std::vector<glm::vec3>& vertices, int threads, EmbreeMode mode) : embree_(vertices, threads, mode) {}
    Baseline(const std::vector<const std::vector<glm::vec3>*>& meshes,
             const std::vector<std::pair<std::uint32_t, glm::mat4>>& placements, int threads, EmbreeMode mode)
        : embree_(meshes, placements, threads, mode), instanced_(true) {}

    EmbreeTiming closest(const std::vector<BatchRay>& rays, int passes, std::vector<std::int64_t>& prim,
                         std::vector<float>& t) override {
        prim.assign(rays.size(), -1);
        t.assign(rays.size(), 0.0f);
        return timed(rays.size(), passes, [&](std::size_t b, std::size_t e) {
            RTCRayHit rh[kBlock];
            for (std::size_t i = b; i < e; ++i) {
                init_ray(rh[i - b].ray, rays[i]);
                rh[i - b].hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh[i - b].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            }
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            rtcIntersect1M(embree_.scene(), &ctx, rh, unsigned(e - b), sizeof(RTCRayHit));
            for (std::size_t i = b; i < e; ++i) {
                const RTCRayHit& h = rh[i - b];
                prim[i] = h.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1
                          : instanced_ ? std::int64_t(h.hit.instID[0]) << 32 | std::int64_t(h.hit.primID)
                                       : std::int64_t(h.hit.primID);
                t[i] = h.ray.tfar;
            }
        });
    }

    EmbreeTiming any(const std::vector<BatchRay>& rays, int passes, std::vector<char>& occluded) override {
        occluded.assign(rays.size(), 0);
        return timed(rays.size(), passes, [&](std::size_t b, std::size_t e) {
            RTCRay r[kBlock];
            for (std::size_t i = b; i < e; ++i) init_ray(r[i - b], rays[i]);
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            rtcOccluded1M(embree_.scene(), &ctx, r, unsigned(e - b), sizeof(RTCRay));
            for (std::size_t i = b; i < e; ++i) occluded[i] = r[i - b].tfar < 0;  // Embree sets -inf on a hit
        });
    }

    std::string describe() const override {
        char buf[200];
        std::snprintf(buf, sizeof buf, "Embree %s, %s, high-quality BVH%s, %d thread%s (FTZ/DAZ), built in %.0f ms",
                      RTC_VERSION_STRING, describe_embree_mode(embree_.mode()).c_str(),
                      instanced_ ? "s placed by instances" : "", embree_.threads(),
                      embree_.threads() == 1 ? "" : "s", embree_.build_ms());
        return buf;
    }
    EmbreeMode mode() const override { return embree_.mode(); }

private:
    EmbreeScene embree_;
    bool instanced_ = false;

    // One warm-up pass and `passes` timed ones; each pass: the threads take blocks of kBlock rays in turn.
    template <class Trace>
    EmbreeTiming timed(std::size_t n, int passes, Trace trace) {
        EmbreeTiming timing;
        for (int p = 0; p <= passes; ++p) {
            std::atomic<std::size_t> next{0};
            auto work = [&] {
                const EmbreeThreadFloatMode ftz_daz;
                for (std::size_t b; (b = next.fetch_add(kBlock)) < n;) trace(b, std::min(n, b + kBlock));
            };
            const auto t0 = std::chrono::steady_clock::now();
            std::vector<std::thread> pool;
            try {
                for (int i = 1; i < embree_.threads(); ++i) pool.emplace_back(work);
            } catch (const std::system_error& e) {
                for (auto& th : pool) th.join();
                throw Error(std::string("Embree baseline: cannot start a thread (") + e.what() + ")");
            }
            work();
            for (auto& th : pool) th.join();
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            if (p > 0) timing.pass_ms.push_back(ms);
        }
        embree_.check("tracing");
        double sum = 0;
        timing.best_ms = timing.pass_ms.empty() ? 0 : timing.pass_ms[0];
        for (double ms : timing.pass_ms) {
            sum += ms;
            timing.best_ms = std::min(timing.best_ms, ms);
        }
        timing.mean_ms = timing.pass_ms.empty() ? 0 : sum / double(timing.pass_ms.size());
        timing.mrays_per_s = timing.mean_ms > 0 ? double(n) / (timing.mean_ms * 1e-3) * 1e-6 : 0;
        return timing;
    }
};

}  // namespace

std::unique_ptr<EmbreeBaseline> make_embree_baseline(const std::vector<glm::vec3>& vertices, EmbreeMode mode,
                                                     int threads) {
    return std::make_unique<Baseline>(vertices, threads, mode);
}

std::unique_ptr<EmbreeBaseline> make_embree_instanced_baseline(
    const std::vector<const std::vector<glm::vec3>*>& meshes,
    const std::vector<std::pair<std::uint32_t, glm::mat4>>& placements, EmbreeMode mode, int threads) {
    return std::make_unique<Baseline>(meshes, placements, threads, mode);
}

#endif

}  // namespace clpath
