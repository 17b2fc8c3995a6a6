// Chunks of samples: the plan covers every sample once, the queue stops at the
// plan's end, at the time budget, on stop(), and skips chunks already done.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "render/chunks.hpp"

namespace clpath {
namespace {

TEST(Chunks, PlanCoversEverySampleOnce) {
    for (std::uint64_t total : {1u, 7u, 64u, 100u, 4097u})
        for (std::uint32_t size : {1u, 3u, 16u, 64u}) {
            ChunkPlan plan{total, size};
            std::uint64_t next = 0;
            for (std::uint64_t k = 0; k < plan.chunk_count(); ++k) {
                const Chunk c = plan.chunk(k);
                ASSERT_EQ(c.first_sample, next);
                ASSERT_GT(c.samples, 0u);
                next += c.samples;
            }
            EXPECT_EQ(next, total) << total << " in chunks of " << size;
        }
}

TEST(Chunks, DefaultSizeDependsOnTheSampleCountOnly) {
    EXPECT_EQ(default_chunk_samples(1), 1u);
    EXPECT_EQ(default_chunk_samples(64), 1u);
    EXPECT_EQ(default_chunk_samples(1024), 16u);
    EXPECT_EQ(default_chunk_samples(1u << 20), 64u);
}

TEST(Chunks, QueueHandsOutEachChunkOnceAcrossThreads) {
    ChunkQueue q({1000, 3}, 0);
    std::vector<std::vector<std::uint64_t>> got(4);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            while (auto c = q.next()) got[std::size_t(t)].push_back(c->index);
        });
    for (auto& t : threads) t.join();
    std::vector<int> seen(ChunkPlan{1000, 3}.chunk_count(), 0);
    for (const auto& g : got)
        for (auto k : g) ++seen[k];
    for (int s : seen) EXPECT_EQ(s, 1);
}

TEST(Chunks, QueueSkipsChunksAlreadyDone) {
    ChunkQueue q({10, 1}, 0, {0, 3, 9});
    std::vector<std::uint64_t> got;
    while (auto c = q.next()) got.push_back(c->index);
    EXPECT_EQ(got, (std::vector<std::uint64_t>{1, 2, 4, 5, 6, 7, 8}));
}

// On a fake clock: the budget counts from the first chunk handed out, the
// last chunk is handed out just before the deadline, none at or after it.
TEST(Chunks, QueueStopsAtTheDeadlineAndOnStop) {
    using namespace std::chrono_literals;
    auto now = std::chrono::steady_clock::time_point{} + 1h;
    ChunkQueue timed({0, 1}, 0.05, {}, [&] { return now; });  // unbounded plan, 50 ms budget
    now += 10s;  // before the first chunk: kernel compiles and uploads do not count
    EXPECT_EQ(timed.seconds_since_start(), 0.0);
    ASSERT_TRUE(timed.next().has_value());
    now += 49ms;
    EXPECT_NEAR(timed.seconds_since_start(), 0.049, 1e-9);
    EXPECT_TRUE(timed.next().has_value());
    now += 1ms;
    EXPECT_FALSE(timed.next().has_value());
    now += 1h;
    EXPECT_FALSE(timed.next().has_value());

    ChunkQueue stopped({100, 1}, 0);
    EXPECT_TRUE(stopped.next().has_value());
    stopped.stop();
    EXPECT_FALSE(stopped.next().has_value());
}

// The real clock is the default: the time since the first chunk passes in real
// time (only a lower bound is checked: a busy machine makes it longer).
TEST(Chunks, QueueDefaultClockIsTheSteadyClock) {
    ChunkQueue timed({0, 1}, 3600);
    ASSERT_TRUE(timed.next().has_value());
    const auto after = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - after < std::chrono::milliseconds(2)) {
    }
    EXPECT_GE(timed.seconds_since_start(), 0.002);
    EXPECT_TRUE(timed.next().has_value());
}

}  // namespace
}  // namespace clpath
