// fork_join (bvh/fork_join.hpp), the builder's threads: every index runs
// once, and an exception from any thread, the calling one included, comes back
// to the caller after every thread has been joined, instead of ending the
// program.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "bvh/fork_join.hpp"

namespace clpath::bvh_build {
namespace {

TEST(ForkJoin, RunsEveryIndexOnce) {
    for (int threads : {1, 2, 5}) {
        std::vector<std::atomic<int>> runs(static_cast<std::size_t>(threads));
        fork_join(threads, [&](int t) { ++runs[std::size_t(t)]; });
        for (int t = 0; t < threads; ++t) EXPECT_EQ(runs[std::size_t(t)].load(), 1) << threads << " threads";
    }
}

TEST(ForkJoin, AWorkersExceptionReachesTheCallerAfterAllFinish) {
    for (int thrower : {0, 1, 3}) {
        std::atomic<int> finished{0};
        try {
            fork_join(4, [&](int t) {
                if (t == thrower) throw std::runtime_error("thread " + std::to_string(t));
                ++finished;
            });
            ADD_FAILURE() << "no exception from thread " << thrower;
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "thread " + std::to_string(thrower));
        }
        EXPECT_EQ(finished.load(), 3) << "the others ran to the end before the rethrow";
    }
}

TEST(ForkJoin, OneThreadThrowsStraightThrough) {
    EXPECT_THROW(fork_join(1, [](int) { throw std::logic_error("alone"); }), std::logic_error);
}

}  // namespace
}  // namespace clpath::bvh_build
