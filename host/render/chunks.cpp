#include "render/chunks.hpp"

#include <algorithm>

#include "util/error.hpp"

namespace clpath {

std::uint64_t ChunkPlan::chunk_count() const {
    if (total_samples == 0) return 0;
    return (total_samples + chunk_samples - 1) / chunk_samples;
}

Chunk ChunkPlan::chunk(std::uint64_t index) const {
    Chunk c;
    c.index = index;
    const std::uint64_t first = index * chunk_samples;
    if (first > 0xffffffffull) throw Error("a render cannot go past 2^32 samples per pixel");
    c.first_sample = std::uint32_t(first);
    std::uint64_t n = chunk_samples;
    if (total_samples) n = std::min<std::uint64_t>(n, total_samples - first);
    n = std::min<std::uint64_t>(n, 0x100000000ull - first);
    c.samples = std::uint32_t(n);
    return c;
}

std::uint32_t default_chunk_samples(std::uint64_t total_samples) {
    if (total_samples == 0) return 4;  // a time budget: small chunks keep it closely
    return std::uint32_t(std::clamp<std::uint64_t>(total_samples / 64, 1, 64));
}

ChunkQueue::ChunkQueue(ChunkPlan plan, double time_budget_seconds, std::vector<std::uint64_t> done, Clock clock)
    : plan_(plan), has_deadline_(time_budget_seconds > 0), done_(std::move(done)), clock_(std::move(clock)) {
    if (!clock_) clock_ = [] { return std::chrono::steady_clock::now(); };
    if (plan_.chunk_samples == 0) throw Error("internal: chunks of 0 samples");
    std::sort(done_.begin(), done_.end());
    budget_ = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(has_deadline_ ? time_budget_seconds : 0));
}

double ChunkQueue::seconds_since_start() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!started_) return 0;
    return std::chrono::duration<double>(clock_() - (deadline_ - budget_)).count();
}

std::optional<Chunk> ChunkQueue::next() {
    std::lock_guard<std::mutex> lock(mutex_);
    // The budget starts with the first chunk, so that kernel compiles and
    // uploads do not eat into it.
    if (!started_) {
        started_ = true;
        deadline_ = clock_() + budget_;
    }
    for (;;) {
        if (stopped_) return std::nullopt;
        if (has_deadline_ && clock_() >= deadline_) return std::nullopt;
        const std::uint64_t count = plan_.chunk_count();
        if (count && next_ >= count) return std::nullopt;
        if (std::uint64_t(next_) * plan_.chunk_samples >= 0x100000000ull) return std::nullopt;
        const std::uint64_t k = next_++;
        if (std::binary_search(done_.begin(), done_.end(), k)) continue;
        return plan_.chunk(k);
    }
}

}  // namespace clpath
