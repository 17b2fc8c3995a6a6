#include "bench/ray_files.hpp"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "util/error.hpp"

namespace clpath {
namespace {

// Little-endian whatever the host's order, so the files read the same everywhere.
void put32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xff);
}

void put_float(std::string& out, float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    put32(out, v);
}

}  // namespace

std::string ray_file_name(RayBatchKind kind) {
    switch (kind) {
        case RayBatchKind::Primary: return "primary.rays";
        case RayBatchKind::Shadow: return "shadow.rays";
        case RayBatchKind::Diffuse: return "diffuse.rays";
    }
    throw Error("internal: unknown ray batch");
}

void check_ray_folder(const std::string& dir, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (dir.empty()) throw Error(what + ": empty folder name");
    if (!fs::exists(dir, ec)) throw Error(what + " " + dir + ": folder does not exist");
    if (!fs::is_directory(dir, ec)) throw Error(what + " " + dir + ": is a file, not a folder");
    if (::access(dir.c_str(), W_OK) != 0) throw Error(what + " " + dir + ": folder is not writable");
}

std::string encode_ray_file(RayBatchKind kind, const std::vector<BatchRay>& rays, const std::vector<float>& result) {
    if (result.size() != rays.size()) throw Error("internal: one result per ray is needed");
    std::string out = "CLPRAYS1";
    out.reserve(32 + 32 * rays.size());
    put32(out, std::uint32_t(kind));
    put32(out, kind == RayBatchKind::Shadow ? 1u : 0u);
    const std::uint64_t n = rays.size();
    put32(out, std::uint32_t(n & 0xffffffffu));
    put32(out, std::uint32_t(n >> 32));
    put32(out, 32);
    put32(out, 0);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const BatchRay& r = rays[i];
        for (float f : {r.o[0], r.o[1], r.o[2], r.tmax, r.d[0], r.d[1], r.d[2], result[i]}) put_float(out, f);
    }
    return out;
}

std::vector<float> closest_hit_results(const std::vector<Hit>& hits) {
    std::vector<float> r(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) r[i] = hits[i].tri < 0 ? INFINITY : hits[i].t;
    return r;
}

std::vector<float> any_hit_results(const std::vector<int>& occluder) {
    std::vector<float> r(occluder.size());
    for (std::size_t i = 0; i < occluder.size(); ++i) r[i] = occluder[i] >= 0 ? 1.0f : 0.0f;
    return r;
}

}  // namespace clpath
