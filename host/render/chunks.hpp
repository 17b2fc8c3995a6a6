#pragma once
// Samples handed out in fixed chunks of sample indices. A chunk's samples are
// the same whichever device renders it (each sample's random numbers depend
// on its pixel, index and the seed alone), and chunk totals are merged exactly
// (render/exact_film.hpp), so an image does not depend on how chunks were
// shared out. A fast device simply takes more chunks: load balance with no
// calibration run.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

namespace clpath {

struct Chunk {
    std::uint64_t index = 0;
    std::uint32_t first_sample = 0;
    std::uint32_t samples = 0;
};

// Chunk k covers samples [k * chunk_samples, min((k + 1) * chunk_samples, total)).
// total 0: unbounded (a time budget ends the render).
struct ChunkPlan {
    std::uint64_t total_samples = 0;
    std::uint32_t chunk_samples = 1;
    std::uint64_t chunk_count() const;  // 0 when unbounded
    Chunk chunk(std::uint64_t index) const;
};

// The chunk size a render uses when the user names none: a function of the
// sample count alone (never of the devices), so that one device and many give
// the same chunks. About 64 chunks, at most 64 samples each.
std::uint32_t default_chunk_samples(std::uint64_t total_samples);

// Anything chunks come from: a local queue, or rank 0 of an MPI job.
class ChunkSource {
public:
    virtual ~ChunkSource() = default;
    // The next chunk to render, or nothing when the render is over.
    virtual std::optional<Chunk> next() = 0;
};

// The queue of one process: chunks in index order, until the plan is done,
// the time budget is spent (counted from the first chunk handed out; no chunk
// is started after it), or stop() is called.
// Chunks listed as done (a resumed render) are skipped. Thread-safe.
class ChunkQueue : public ChunkSource {
public:
    using Clock = std::function<std::chrono::steady_clock::time_point()>;
    // clock: the time the budget is counted in; default steady_clock::now
    // (tests pass a fake one, so that a deadline does not depend on scheduling).
    ChunkQueue(ChunkPlan plan, double time_budget_seconds, std::vector<std::uint64_t> done = {}, Clock clock = {});
    std::optional<Chunk> next() override;
    void stop() { stopped_ = true; }
    // Seconds since the first chunk was handed out (0 before).
    double seconds_since_start();
    bool stopped() const { return stopped_; }

private:
    ChunkPlan plan_;
    std::chrono::steady_clock::duration budget_{};
    std::chrono::steady_clock::time_point deadline_{};
    bool has_deadline_, started_ = false;
    std::vector<std::uint64_t> done_;  // sorted
    std::mutex mutex_;
    std::uint64_t next_ = 0;
    std::atomic<bool> stopped_{false};
    Clock clock_;
};

}  // namespace clpath
