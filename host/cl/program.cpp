#include "cl/program.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "util/error.hpp"

namespace clpath {
namespace fs = std::filesystem;
namespace {

constexpr int kCacheFormat = 1;

fs::path cache_dir() {
    if (const char* d = std::getenv("CLPATH_CACHE_DIR"); d && *d) {
        if (std::string(d) == "off") return {};
        return d;
    }
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "clpath";
    if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "clpath";
    return {};
}

std::string build_log(cl_program p, cl_device_id d) {
    std::size_t n = 0;
    clGetProgramBuildInfo(p, d, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
    std::string log(n, '\0');
    clGetProgramBuildInfo(p, d, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

// Builds p; on failure throws with the log. Returns false (and does not throw)
// only for a cached binary the driver rejects, so the caller can compile anew.
bool build_or_throw(cl_program p, const DeviceInfo& dev, const std::string& options, bool from_binary) {
    cl_int err = clBuildProgram(p, 1, &dev.device, options.c_str(), nullptr, nullptr);
    if (err == CL_SUCCESS) return true;
    if (from_binary) return false;
    std::string log = build_log(p, dev.device);
    throw Error("kernel build failed on " + dev.name + ": " + cl_error_name(err) + "\n--- build log ---\n" +
                (log.empty() ? "(empty)" : log) + "\n--- end of build log ---");
}

std::vector<unsigned char> program_binary(cl_program p) {
    std::size_t n = 0;
    cl_check(clGetProgramInfo(p, CL_PROGRAM_BINARY_SIZES, sizeof n, &n, nullptr), "CL_PROGRAM_BINARY_SIZES");
    std::vector<unsigned char> bin(n);
    unsigned char* ptr = bin.data();
    cl_check(clGetProgramInfo(p, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr), "CL_PROGRAM_BINARIES");
    return bin;
}

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t h) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

std::uint64_t fnv1a64(const std::string& data, std::uint64_t h) { return fnv1a64(data.data(), data.size(), h); }

BuildResult build_program(Context& ctx, const std::string& source, const std::string& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const DeviceInfo& dev = ctx.device();
    BuildResult result;

    std::ostringstream key;
    key << std::hex
        << fnv1a64(source + '\x1f' + options + '\x1f' + dev.name + '\x1f' + dev.platform_name + '\x1f' +
                   dev.version + '\x1f' + dev.driver + '\x1f' + std::to_string(kCacheFormat));
    const fs::path dir = cache_dir();
    const fs::path file = dir.empty() ? fs::path() : dir / (key.str() + ".bin");

    // Cached binary first.
    if (!file.empty()) {
        std::ifstream in(file, std::ios::binary);
        std::vector<unsigned char> bin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!bin.empty()) {
            const unsigned char* ptr = bin.data();
            std::size_t n = bin.size();
            cl_int status = CL_SUCCESS, err = CL_SUCCESS;
            cl_program p = clCreateProgramWithBinary(ctx.get(), 1, &dev.device, &n, &ptr, &status, &err);
            if (err == CL_SUCCESS && status == CL_SUCCESS && build_or_throw(p, dev, options, true)) {
                result.program = Program(p);
                result.from_cache = true;
            } else if (p) {
                clReleaseProgram(p);
            }
        }
    }

    if (!result.program.get()) {
        const char* src = source.c_str();
        std::size_t len = source.size();
        cl_int err = CL_SUCCESS;
        cl_program p = clCreateProgramWithSource(ctx.get(), 1, &src, &len, &err);
        cl_check(err, "clCreateProgramWithSource");
        Program owned(p);
        build_or_throw(p, dev, options, false);
        result.program = std::move(owned);
        // Best effort: a cache that cannot be written only costs time.
        if (!file.empty()) {
            std::error_code ec;
            fs::create_directories(dir, ec);
            const auto bin = program_binary(result.program.get());
            const fs::path tmp = file.string() + ".tmp" + std::to_string(::getpid());
            {
                std::ofstream out(tmp, std::ios::binary);
                out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
                if (!out) ec = std::make_error_code(std::errc::io_error);
            }
            if (!ec) fs::rename(tmp, file, ec);  // atomic: readers never see half a file
            if (ec) fs::remove(tmp, ec);
        }
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace clpath
