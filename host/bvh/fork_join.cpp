#include "bvh/fork_join.hpp"

#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "util/error.hpp"

namespace clpath::bvh_build {

void fork_join(int threads, const std::function<void(int)>& f) {
    if (threads <= 1) {
        f(0);
        return;
    }
    // An exception must not leave a thread: one escaping a worker would end
    // the program (std::terminate), and one from the calling thread would
    // leave the workers unjoined (the same). Each is caught, every thread
    // joined, and the first rethrown here.
    std::mutex mutex;
    std::exception_ptr first;
    auto guarded = [&](int t) {
        try {
            f(t);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!first) first = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(std::size_t(threads - 1));
    try {
        for (int t = 1; t < threads; ++t) pool.emplace_back(guarded, t);
    } catch (const std::system_error& e) {
        for (auto& th : pool) th.join();
        throw Error(std::string("BVH build: cannot start a thread (") + e.what() + ")");
    }
    guarded(0);
    for (auto& th : pool) th.join();
    if (first) std::rethrow_exception(first);
}

}  // namespace clpath::bvh_build
