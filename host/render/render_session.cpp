#include "render/render_session.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "render/checkpoint.hpp"
#include "render/chunks.hpp"
#include "render/process_group.hpp"
#include "render/render_hash.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// The sums and chunks a resumed render starts from, checked against this render.
Checkpoint resumed(const std::string& path, std::uint64_t hash, const ChunkPlan& plan, const Camera& camera) {
    Checkpoint c = read_checkpoint(path);
    if (c.render_hash != hash) throw CheckpointError(path + ": the checkpoint is of another scene or other settings");
    if (c.plan.total_samples != plan.total_samples || c.plan.chunk_samples != plan.chunk_samples)
        throw CheckpointError(path + ": the checkpoint is of a render of " + std::to_string(c.plan.total_samples) +
                              " samples in chunks of " + std::to_string(c.plan.chunk_samples) + "; give the same --spp" +
                              " and --chunk to continue it");
    if (c.film.width() != camera.width || c.film.height() != camera.height)
        throw CheckpointError(path + ": the checkpoint is of another image size");
    return c;
}

}  // namespace

SessionResult render_session(const Scene& scene, const RenderSettings& settings,
                             const std::vector<DeviceInfo>& devices, const SessionOptions& o,
                             const SessionHooks& hooks, ProcessGroup* group) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool lead = !group || group->leads();
    if (group && group->size() > 1 && (o.checkpoint_seconds > 0 || !o.resume_path.empty()))
        throw Error("--checkpoint and --resume work in one process; over MPI ranks, render shorter jobs instead");

    const std::uint64_t hash = render_hash(scene, settings);
    const ChunkPlan plan{o.spp, o.chunk_samples ? o.chunk_samples : default_chunk_samples(o.spp)};
    ExactFilm start;
    std::vector<std::uint64_t> done;
    SessionResult r;
    r.leads = lead;
    if (!o.resume_path.empty()) {
        Checkpoint c = resumed(o.resume_path, hash, plan, scene.camera);
        start = std::move(c.film);
        done = std::move(c.done_chunks);
        r.resumed_spp = start.samples_per_pixel();
        if (hooks.on_resumed) hooks.on_resumed(r.resumed_spp);
    }
    if (group) group->check_same(hash, "the scene and render settings");

    DeviceFarm farm(devices, scene, settings, std::move(start), done);
    if (hooks.on_start) hooks.on_start(farm.bvh_stats());
    ChunkQueue queue(plan, o.time_limit, done);
    farm.start(group ? group->chunk_source(queue) : queue, hooks.on_chunk);

    auto last_checkpoint = std::chrono::steady_clock::now();
    std::uint64_t checkpointed_spp = farm.samples_per_pixel();
    auto save_checkpoint = [&] {
        Checkpoint c;
        c.render_hash = hash;
        c.plan = plan;
        c.film = farm.snapshot(&c.done_chunks);
        std::sort(c.done_chunks.begin(), c.done_chunks.end());
        write_checkpoint(o.checkpoint_path, c);
        checkpointed_spp = c.film.samples_per_pixel();
        last_checkpoint = std::chrono::steady_clock::now();
    };
    auto poll = [&] {
        if (!r.stopped && hooks.stop_requested && hooks.stop_requested()) {
            r.stopped = true;
            queue.stop();
            farm.cancel();
        }
        if (hooks.on_progress) hooks.on_progress(farm.samples_per_pixel());
        // A checkpoint is written when there is something new to keep.
        if (o.checkpoint_seconds > 0 && farm.samples_per_pixel() > checkpointed_spp &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                o.checkpoint_seconds)
            save_checkpoint();
    };
    try {
        if (group)
            group->run_chunks(queue, farm, poll);
        else
            while (!farm.finished()) {
                poll();
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
    } catch (...) {
        farm.cancel();
        queue.stop();
        throw;
    }
    farm.wait();
    // A stopped render keeps all it did: resuming it loses no finished chunk.
    if (r.stopped && o.checkpoint_seconds > 0 && farm.samples_per_pixel() > checkpointed_spp) save_checkpoint();
    r.wall_seconds = lead ? queue.seconds_since_start()
                          : std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.film = farm.snapshot();
    r.shares = farm.shares();
    r.bvh = farm.bvh_stats();
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
