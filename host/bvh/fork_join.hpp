#pragma once
// The BVH builder's threads: a fork and a join, no pool. A build starts a
// handful of parallel passes (the records, each top level's binning and
// scatter, the subtrees, the output), so starting threads per pass costs
// microseconds against passes of milliseconds, and nothing outlives a build.
#include <functional>

namespace clpath::bvh_build {

// f(t) for t in [0, threads): t = 0 on the calling thread, the others on their own.
// Throws clpath::Error when a thread cannot be started.
void fork_join(int threads, const std::function<void(int)>& f);

}  // namespace clpath::bvh_build
