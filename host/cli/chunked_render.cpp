#include "cli/chunked_render.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "cli/interrupt.hpp"
#include "cli/progress.hpp"
#include "render/checkpoint.hpp"
#include "render/chunks.hpp"
#include "render/render_hash.hpp"
#include "util/error.hpp"
#ifdef CLPATH_WITH_MPI
#include "mpi/mpi_job.hpp"
#endif

namespace clpath {

ChunkedRenderResult render_in_chunks(const Scene& scene, const RenderSettings& settings,
                                     const std::vector<DeviceInfo>& devices, const ChunkedRenderOptions& o,
                                     MpiJob* mpi) {
    const auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const bool distributed = mpi != nullptr;
#ifdef CLPATH_WITH_MPI
    const bool lead = !mpi || mpi->rank() == 0;
#else
    const bool lead = true;
#endif
    if (distributed && (o.checkpoint_seconds > 0 || !o.resume_path.empty()))
        throw Error("--checkpoint and --resume work in one process; over MPI ranks, render shorter jobs instead");

    const std::uint64_t hash = render_hash(scene, settings);
    ChunkPlan plan{o.spp, o.chunk_samples ? o.chunk_samples : default_chunk_samples(o.spp)};
    ExactFilm start;
    std::vector<std::uint64_t> done;
    if (!o.resume_path.empty()) {
        Checkpoint c = read_checkpoint(o.resume_path);
        if (c.render_hash != hash)
            throw Error(o.resume_path + ": the checkpoint is of another scene or other settings");
        if (c.plan.total_samples != plan.total_samples || c.plan.chunk_samples != plan.chunk_samples)
            throw Error(o.resume_path + ": the checkpoint is of a render of " + std::to_string(c.plan.total_samples) +
                        " samples in chunks of " + std::to_string(c.plan.chunk_samples) + "; give the same --spp" +
                        " and --chunk to continue it");
        if (c.film.width() != scene.camera.width || c.film.height() != scene.camera.height)
            throw Error(o.resume_path + ": the checkpoint is of another image size");
        start = std::move(c.film);
        done = std::move(c.done_chunks);
    }
#ifdef CLPATH_WITH_MPI
    if (mpi) mpi->check_same(hash, "the scene and render settings");
#endif

    ChunkedRenderResult r;
    r.writes_output = lead;
    DeviceFarm farm(devices, scene, settings, std::move(start), done);
    if (o.progress && lead) std::fprintf(stderr, "clpath: %s\n", describe(farm.bvh_stats()).c_str());
    ChunkQueue queue(plan, o.time_limit, done);
#ifdef CLPATH_WITH_MPI
    RemoteChunks remote;
    farm.start(lead ? static_cast<ChunkSource&>(queue) : static_cast<ChunkSource&>(remote));
#else
    farm.start(queue);
#endif

    InterruptFlag interrupt;
    // Progress keeps its own clock, started here: the queue's starts with the
    // first chunk, and a log should show lines while the devices get ready too.
    ProgressOptions po;
    po.log_interval = o.progress_interval;
    Progress progress(o.spp, o.time_limit, o.progress && lead, po);
    auto last_checkpoint = std::chrono::steady_clock::now();
    std::uint64_t checkpointed_spp = farm.samples_per_pixel();
    auto poll = [&] {
        if (interrupt.raised() && !r.interrupted) {
            r.interrupted = true;
            r.signal = interrupt.signal();
            queue.stop();
            farm.cancel();
        }
        progress.update(farm.samples_per_pixel());
        // A checkpoint is written when there is something new to keep.
        if (o.checkpoint_seconds > 0 && farm.samples_per_pixel() > checkpointed_spp &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                o.checkpoint_seconds) {
            Checkpoint c;
            c.render_hash = hash;
            c.plan = plan;
            c.film = farm.snapshot(&c.done_chunks);
            std::sort(c.done_chunks.begin(), c.done_chunks.end());
            write_checkpoint(o.checkpoint_path, c);
            checkpointed_spp = c.film.samples_per_pixel();
            last_checkpoint = std::chrono::steady_clock::now();
        }
    };
    try {
#ifdef CLPATH_WITH_MPI
        if (mpi)
            mpi->run_chunks(lead ? &queue : nullptr, lead ? nullptr : &remote, farm, poll);
        else
#endif
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
    progress.finish();
    // Rendering time, from the first chunk: kernel compiles and uploads are not in it.
    r.wall_seconds = lead ? queue.seconds_since_start() : elapsed();
    r.film = farm.snapshot();
    r.shares = farm.shares();
    r.bvh = farm.bvh_stats();
#ifdef CLPATH_WITH_MPI
    if (mpi) {
        mpi->reduce_film(r.film);
        r.shares = mpi->gather_shares(r.shares);
    }
#endif
    for (const auto& s : r.shares) {
        r.rays += s.rays;
        r.nonfinite += s.nonfinite;
    }
    return r;
}

}  // namespace clpath
