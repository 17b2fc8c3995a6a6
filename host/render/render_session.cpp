#include "render/render_session.hpp"

#include <algorithm>
#include <bit>
#include <mutex>
#include <optional>
#include <chrono>
#include <memory>
#include <thread>

#include "render/adaptive_passes.hpp"
#include "render/checkpoint.hpp"
#include "render/chunks.hpp"
#include "render/process_group.hpp"
#include "render/render_hash.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// The sums and chunks a resumed render starts from, checked against this render.
Checkpoint resumed(const std::string& path, std::uint64_t hash, const ChunkPlan& plan, const Camera& camera,
                   double noise_target) {
    Checkpoint c = read_checkpoint(path);
    if (c.render_hash != hash) throw CheckpointError(path + ": the checkpoint is of another scene or other settings");
    if (c.noise_target != noise_target)
        throw CheckpointError(path + ": the checkpoint is of a render " +
                    (c.noise_target > 0 ? "to the noise target " + std::to_string(c.noise_target)
                                        : std::string("without a noise target")) +
                    "; give the same --noise-target to continue it");
    if (c.plan.total_samples != plan.total_samples || c.plan.chunk_samples != plan.chunk_samples)
        throw CheckpointError(path + ": the checkpoint is of a render of " + std::to_string(c.plan.total_samples) +
                              " samples in chunks of " + std::to_string(c.plan.chunk_samples) + "; give the same --spp" +
                              " and --chunk to continue it");
    if (c.film.width() != camera.width || c.film.height() != camera.height)
        throw CheckpointError(path + ": the checkpoint is of another image size");
    return c;
}

// A process's share of the chunks when the processes of a group take fixed
// shares (adaptive sampling over MPI ranks): chunk k goes to rank k % size.
class RankChunks : public ChunkSource {
public:
    RankChunks(ChunkSource& all, int rank, int size) : all_(all), rank_(std::uint64_t(rank)), size_(std::uint64_t(size)) {}
    std::optional<Chunk> next() override {
        std::lock_guard<std::mutex> lock(mutex_);
        for (;;) {
            std::optional<Chunk> c = all_.next();
            if (!c || c->index % size_ == rank_) return c;
        }
    }
    // Chunks of [first, first + count) that are this rank's.
    std::uint64_t share(std::uint64_t first, std::uint64_t count) const {
        std::uint64_t n = 0;
        for (std::uint64_t k = first; k < first + count; ++k) n += k % size_ == rank_;
        return n;
    }

private:
    ChunkSource& all_;
    std::uint64_t rank_, size_;
    std::mutex mutex_;
};

}  // namespace

SessionResult render_session(const Scene& scene, const RenderSettings& settings,
                             const std::vector<DeviceInfo>& devices, const SessionOptions& o,
                             const SessionHooks& hooks, ProcessGroup* group) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool lead = !group || group->leads();
    if (group && group->size() > 1 && (o.checkpoint_seconds > 0 || !o.resume_path.empty()))
        throw Error("--checkpoint and --resume work in one process; over MPI ranks, render shorter jobs instead");

    const std::uint64_t hash = render_hash(scene, settings);
    const bool adaptive = o.noise_target > 0;
    // Adaptive over processes: each renders the chunks k with k % size ==
    // rank (RankChunks), and at every pass boundary all add their films
    // (sum_films), so each holds the same film and takes the same decision.
    // A time budget would end the ranks at different chunks of a pass.
    const bool ranks = group && group->size() > 1;
    if (adaptive && ranks && (o.spp == 0 || o.time_limit > 0))
        throw UsageError("--noise-target over MPI ranks needs --spp and no --time (the ranks must end at the same pass)");
    std::uint32_t chunk_samples = o.chunk_samples ? o.chunk_samples : default_chunk_samples(o.spp);
    // Adaptive: decisions every pass of 4 chunks, so chunks of at most 8
    // samples (a decision every 32); the half film needs an even number.
    if (adaptive && !o.chunk_samples) chunk_samples = std::clamp<std::uint32_t>(chunk_samples + chunk_samples % 2, 2, 8);
    const ChunkPlan plan{o.spp, chunk_samples};
    std::unique_ptr<AdaptivePasses> passes;
    if (adaptive) {
        try {
            passes = std::make_unique<AdaptivePasses>(plan, o.noise_target, scene.camera.width, scene.camera.height,
                                                      o.adaptive_rule);
        } catch (const Error& e) {
            throw UsageError(std::string("--noise-target: ") + e.what());
        }
    }
    ExactFilm start;
    std::vector<std::uint64_t> done;
    SessionResult r;
    r.leads = lead;
    if (!o.resume_path.empty()) {
        Checkpoint c = resumed(o.resume_path, hash, plan, scene.camera, o.noise_target);
        if (passes) {
            try {
                passes->resume(c.film, c.done_chunks);
            } catch (const Error& e) {
                throw Error(o.resume_path + ": " + e.what());
            }
        }
        start = std::move(c.film);
        done = std::move(c.done_chunks);
        r.resumed_spp = start.samples_per_pixel();
        if (hooks.on_resumed) hooks.on_resumed(r.resumed_spp);
    }
    if (group) {
        group->check_same(hash, "the scene and render settings");
        group->check_same(std::bit_cast<std::uint64_t>(o.noise_target), "--noise-target");
    }

    DeviceFarm farm(devices, scene, settings, std::move(start), done);
    if (hooks.on_start) hooks.on_start(farm.bvh_stats());
    ChunkQueue queue(plan, o.time_limit, done);
    if (passes) {
        farm.use_passes(kAdaptivePassChunks);
        if (passes->converged() || passes->ended()) {
            queue.stop();  // a resumed render that was already done
            farm.close_passes();
        } else {
            farm.open_pass(passes->pass(), passes->mask());
        }
    }
    RankChunks rank_chunks(queue, ranks ? group->rank() : 0, ranks ? group->size() : 1);
    const bool adaptive_ranks = adaptive && ranks;
    farm.start(adaptive_ranks ? rank_chunks : group ? group->chunk_source(queue) : queue, hooks.on_chunk);

    auto last_checkpoint = std::chrono::steady_clock::now();
    std::uint64_t checkpointed_spp = farm.samples_per_pixel();
    auto write = [&](Checkpoint& c) {
        c.render_hash = hash;
        c.plan = plan;
        c.noise_target = o.noise_target;
        std::sort(c.done_chunks.begin(), c.done_chunks.end());
        write_checkpoint(o.checkpoint_path, c);
        checkpointed_spp = c.film.samples_per_pixel();
        last_checkpoint = std::chrono::steady_clock::now();
    };
    auto save_checkpoint = [&] {
        Checkpoint c;
        c.film = farm.snapshot(&c.done_chunks);
        write(c);
    };
    auto checkpoint_due = [&](std::uint64_t spp) {
        return o.checkpoint_seconds > 0 && spp > checkpointed_spp &&
               std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                   o.checkpoint_seconds;
    };
    // Adaptive: the film at the last pass boundary, the only place its
    // checkpoints are taken (a resumed render must decide as this one did).
    Checkpoint boundary;
    auto adaptive_poll = [&] {
        if (passes->converged() || passes->ended() || r.stopped) return;
        std::uint64_t want = passes->chunks_in(passes->pass());
        if (adaptive_ranks) want = rank_chunks.share(passes->pass() * kAdaptivePassChunks, want);
        if (farm.chunks_done_in_pass(passes->pass()) < want) return;
        boundary = Checkpoint{};
        boundary.film = farm.snapshot(&boundary.done_chunks);
        if (adaptive_ranks) {
            if (boundary.film.half().empty()) boundary.film.half().assign(boundary.film.sums().size() / 3, 0);
            group->sum_films(boundary.film);
        }
        const bool more = passes->finish_pass(boundary.film);
        if (more) {
            farm.open_pass(passes->pass(), passes->mask());
        } else if (passes->converged()) {
            r.converged = true;
            queue.stop();
            farm.close_passes();
        }
        if (checkpoint_due(boundary.film.samples_per_pixel())) write(boundary);
    };
    auto poll = [&] {
        if (!r.stopped && hooks.stop_requested && hooks.stop_requested()) {
            r.stopped = true;
            queue.stop();
            farm.cancel();
        }
        if (hooks.on_progress) hooks.on_progress(farm.samples_per_pixel());
        if (passes) return adaptive_poll();
        // A checkpoint is written when there is something new to keep.
        if (checkpoint_due(farm.samples_per_pixel())) save_checkpoint();
    };
    try {
        if (group && !adaptive_ranks)
            group->run_chunks(queue, farm, poll);
        else
            while (!farm.finished()) {
                poll();
                // Adaptive: a pass boundary leaves the devices waiting for this thread's decision.
                std::this_thread::sleep_for(std::chrono::milliseconds(passes ? 1 : 10));
            }
    } catch (...) {
        farm.cancel();
        queue.stop();
        throw;
    }
    farm.wait();
    // A stopped render keeps all it did (an adaptive one, all it did up to its
    // last pass boundary): resuming it loses no finished chunk.
    if (r.stopped && o.checkpoint_seconds > 0) {
        if (!passes && farm.samples_per_pixel() > checkpointed_spp) save_checkpoint();
        if (passes && boundary.film.samples_per_pixel() > checkpointed_spp) write(boundary);
    }
    r.wall_seconds = lead ? queue.seconds_since_start()
                          : std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (passes) {
        // The devices may end before the last pass was seen complete; over
        // ranks, one whose share of the later passes is empty still takes
        // part in their boundaries' sums.
        if (!r.stopped) adaptive_poll();
        while (adaptive_ranks && !r.stopped && !passes->converged() && !passes->ended()) adaptive_poll();
        std::vector<std::uint64_t> final_done;
        r.film = farm.snapshot(&final_done);
        if (r.film.half().empty()) r.film.half().assign(r.film.sums().size() / 3, 0);
        r.film.set_pixel_samples(passes->counts_with(final_done));
        r.converged = passes->converged();
    } else {
        r.film = farm.snapshot();
    }
    r.shares = farm.shares();
    r.bvh = farm.bvh_stats();
    r.instanced = farm.scene_summary().instanced;
    r.instances = farm.scene_summary().instance_stats;
    r.light_bvh = farm.scene_summary().light_bvh;
    r.scene_device_bytes = farm.scene_device_bytes();
    if (group) {
        group->reduce_film(r.film);
        r.shares = group->gather_shares(r.shares);
    }
    for (const auto& s : r.shares) {
        r.rays += s.rays;
        r.nonfinite += s.nonfinite;
        r.bytes_to_device += s.bytes_to_device;
        r.bytes_from_device += s.bytes_from_device;
    }
    return r;
}

}  // namespace clpath
