#pragma once
// Building OpenCL programs, with an on-disk cache of compiled binaries
// (PoCL compiles take seconds; a cached binary loads in milliseconds).
#include <CL/cl.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "cl/context.hpp"

namespace clpath {

class Program {
public:
    Program() = default;
    explicit Program(cl_program p) : p_(p) {}
    Program(Program&& o) noexcept : p_(std::exchange(o.p_, nullptr)) {}
    Program& operator=(Program&& o) noexcept {
        std::swap(p_, o.p_);
        return *this;
    }
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
    ~Program() {
        if (p_) clReleaseProgram(p_);
    }
    cl_program get() const { return p_; }

private:
    cl_program p_ = nullptr;
};

struct BuildResult {
    Program program;
    bool from_cache = false;
    double seconds = 0;
};

// Builds source with options for the context's device. The cache key is a
// hash of the source, the options and the device, platform and driver names
// and versions, so any change to any of them rebuilds. Cache folder:
// $CLPATH_CACHE_DIR, else $XDG_CACHE_HOME/clpath, else ~/.cache/clpath;
// CLPATH_CACHE_DIR=off disables it. A failed compile throws clpath::Error
// with the device's full build log.
BuildResult build_program(Context& ctx, const std::string& source, const std::string& options);

// 64-bit FNV-1a's step (xor a byte, multiply by the FNV prime): a stable hash
// for cache keys and checkpoints (std::hash is not stable across builds). The
// default seed is not FNV's published offset basis (14695981039346656037) but
// that number short of its last digit; it stays, as checkpoints store hashes
// made with it.
constexpr std::uint64_t kFnv1a64Seed = 1469598103934665603ull;
std::uint64_t fnv1a64(const std::string& data, std::uint64_t seed = kFnv1a64Seed);
// The same over bytes in place (a scene's arrays: no copy into a string).
std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed = kFnv1a64Seed);

}  // namespace clpath
