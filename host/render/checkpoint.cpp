#include "render/checkpoint.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <xxhash.h>

#include "util/error.hpp"

namespace clpath {
namespace {

// Format 2 adds the checksum; format 1 files (no checksum) are refused by name.
constexpr char kMagic[8] = {'C', 'L', 'P', 'C', 'K', 'P', 'T', '2'};
constexpr char kMagicV1[8] = {'C', 'L', 'P', 'C', 'K', 'P', 'T', '1'};
// An adaptive render's: the header is followed by the noise target (a
// double), and the sums by the half film and the per-pixel counts.
constexpr char kMagicAdaptive[8] = {'C', 'L', 'P', 'C', 'K', 'P', 'A', '2'};
constexpr std::uint64_t kMaxSide = 16384;

struct Header {
    char magic[8];
    std::uint64_t render_hash;
    std::uint64_t total_samples;
    std::uint64_t chunk_samples;
    std::uint64_t samples_per_pixel;
    std::uint64_t width, height;
    std::uint64_t done_count;
};

// The whole file's size as the header describes it: header, (noise target,)
// chunk list, sums, (half film, counts,) checksum.
std::uint64_t described_size(const Header& h, bool adaptive) {
    const std::uint64_t pixels = h.width * h.height;
    return sizeof(Header) + (adaptive ? sizeof(double) : 0) + h.done_count * 8 + pixels * 3 * sizeof(Fixed128) +
           (adaptive ? pixels * (sizeof(Fixed128) + sizeof(std::uint32_t)) : 0) + sizeof(XXH64_hash_t);
}

// XXH3 (xxHash, Debian's libxxhash) over header, chunk list and sums, in that order.
class Checksum {
public:
    Checksum() : state_(XXH3_createState()) {
        if (!state_ || XXH3_64bits_reset(state_) != XXH_OK) throw Error("internal: xxHash could not start");
    }
    ~Checksum() { XXH3_freeState(state_); }
    Checksum(const Checksum&) = delete;
    Checksum& operator=(const Checksum&) = delete;
    void add(const void* data, std::size_t size) { XXH3_64bits_update(state_, data, size); }
    XXH64_hash_t value() const { return XXH3_64bits_digest(state_); }

private:
    XXH3_state_t* state_;
};

}  // namespace

void write_checkpoint(const std::string& path, const Checkpoint& c) {
    const bool adaptive = c.noise_target > 0;
    const std::size_t pixels = std::size_t(c.film.width()) * std::size_t(c.film.height());
    if (adaptive && (c.film.half().size() != pixels || c.film.pixel_samples().size() != pixels))
        throw Error("internal: an adaptive checkpoint without its half film or sample counts");
    Header h{};
    std::memcpy(h.magic, adaptive ? kMagicAdaptive : kMagic, sizeof kMagic);
    h.render_hash = c.render_hash;
    h.total_samples = c.plan.total_samples;
    h.chunk_samples = c.plan.chunk_samples;
    h.samples_per_pixel = c.film.samples_per_pixel();
    h.width = std::uint64_t(c.film.width());
    h.height = std::uint64_t(c.film.height());
    h.done_count = c.done_chunks.size();
    const std::size_t chunk_bytes = c.done_chunks.size() * 8, sum_bytes = c.film.sums().size() * sizeof(Fixed128);
    const std::size_t half_bytes = adaptive ? pixels * sizeof(Fixed128) : 0;
    const std::size_t count_bytes = adaptive ? pixels * sizeof(std::uint32_t) : 0;
    Checksum sum;
    sum.add(&h, sizeof h);
    if (adaptive) sum.add(&c.noise_target, sizeof c.noise_target);
    sum.add(c.done_chunks.data(), chunk_bytes);
    sum.add(c.film.sums().data(), sum_bytes);
    if (adaptive) {
        sum.add(c.film.half().data(), half_bytes);
        sum.add(c.film.pixel_samples().data(), count_bytes);
    }
    const XXH64_hash_t checksum = sum.value();
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw Error(path + ": cannot write the checkpoint (" + std::strerror(errno) + ")");
        f.write(reinterpret_cast<const char*>(&h), sizeof h);
        if (adaptive) f.write(reinterpret_cast<const char*>(&c.noise_target), sizeof c.noise_target);
        f.write(reinterpret_cast<const char*>(c.done_chunks.data()), std::streamsize(chunk_bytes));
        f.write(reinterpret_cast<const char*>(c.film.sums().data()), std::streamsize(sum_bytes));
        if (adaptive) {
            f.write(reinterpret_cast<const char*>(c.film.half().data()), std::streamsize(half_bytes));
            f.write(reinterpret_cast<const char*>(c.film.pixel_samples().data()), std::streamsize(count_bytes));
        }
        f.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
        f.flush();
        if (!f) {
            std::remove(tmp.c_str());
            throw Error(path + ": writing the checkpoint failed (disk full?)");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw Error(path + ": cannot replace the checkpoint: " + ec.message());
    }
}

Checkpoint read_checkpoint(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw CheckpointError(path + ": cannot open the checkpoint: it is a folder");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw CheckpointError(path + ": cannot open the checkpoint (" + std::strerror(errno) + ")");
    const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
    if (ec) throw CheckpointError(path + ": cannot open the checkpoint (" + ec.message() + ")");
    Header h{};
    f.read(reinterpret_cast<char*>(&h), sizeof h);
    if (!f) throw CheckpointError(path + ": not a clpath checkpoint (shorter than a checkpoint's header)");
    if (std::memcmp(h.magic, kMagicV1, sizeof kMagicV1) == 0)
        throw CheckpointError(path + ": a checkpoint of an older clpath (format 1, without a checksum); it cannot be resumed");
    const bool adaptive = std::memcmp(h.magic, kMagicAdaptive, sizeof kMagicAdaptive) == 0;
    if (!adaptive && std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
        throw CheckpointError(path + ": not a clpath checkpoint");
    // The header is checked against itself and against the file's real size
    // before anything it describes is allocated: a forged one cannot ask for
    // more memory than the file holds.
    if (h.width == 0 || h.height == 0 || h.width > kMaxSide || h.height > kMaxSide || h.chunk_samples == 0 ||
        h.chunk_samples > 0xffffffffull || h.done_count > (1ull << 32))
        throw CheckpointError(path + ": the checkpoint's header is corrupt (image " + std::to_string(h.width) + "x" +
                    std::to_string(h.height) + ", chunks of " + std::to_string(h.chunk_samples) + " samples, " +
                    std::to_string(h.done_count) + " chunks)");
    if (described_size(h, adaptive) != file_size)
        throw CheckpointError(path + ": the checkpoint's header describes " + std::to_string(described_size(h, adaptive)) +
                    " bytes, but the file has " + std::to_string(file_size) + " (truncated, or not written by clpath)");
    Checkpoint c;
    if (adaptive) f.read(reinterpret_cast<char*>(&c.noise_target), sizeof c.noise_target);
    c.render_hash = h.render_hash;
    c.plan.total_samples = h.total_samples;
    c.plan.chunk_samples = std::uint32_t(h.chunk_samples);
    c.done_chunks.resize(h.done_count);
    f.read(reinterpret_cast<char*>(c.done_chunks.data()), std::streamsize(h.done_count * 8));
    c.film = ExactFilm(int(h.width), int(h.height));
    f.read(reinterpret_cast<char*>(c.film.sums().data()), std::streamsize(c.film.sums().size() * sizeof(Fixed128)));
    const std::size_t pixels = std::size_t(h.width) * std::size_t(h.height);
    std::vector<std::uint32_t> counts;
    if (adaptive) {
        c.film.half().assign(pixels, 0);
        f.read(reinterpret_cast<char*>(c.film.half().data()), std::streamsize(pixels * sizeof(Fixed128)));
        counts.resize(pixels);
        f.read(reinterpret_cast<char*>(counts.data()), std::streamsize(pixels * sizeof(std::uint32_t)));
    }
    XXH64_hash_t stored = 0;
    f.read(reinterpret_cast<char*>(&stored), sizeof stored);
    if (!f) throw CheckpointError(path + ": the checkpoint is truncated");
    Checksum sum;
    sum.add(&h, sizeof h);
    if (adaptive) sum.add(&c.noise_target, sizeof c.noise_target);
    sum.add(c.done_chunks.data(), c.done_chunks.size() * 8);
    sum.add(c.film.sums().data(), c.film.sums().size() * sizeof(Fixed128));
    if (adaptive) {
        sum.add(c.film.half().data(), pixels * sizeof(Fixed128));
        sum.add(counts.data(), pixels * sizeof(std::uint32_t));
    }
    if (sum.value() != stored)
        throw CheckpointError(path + ": the checkpoint is damaged: its xxHash checksum does not match its contents");
    if (adaptive) {
        if (!(c.noise_target > 0) || !std::isfinite(c.noise_target))
            throw CheckpointError(path + ": the checkpoint's noise target is corrupt");
        for (std::uint32_t n : counts)
            if (n > h.samples_per_pixel) throw CheckpointError(path + ": the checkpoint's sample counts are corrupt");
        c.film.set_pixel_samples(std::move(counts));
    }
    c.film.set_samples_per_pixel(h.samples_per_pixel);
    for (std::size_t i = 1; i < c.done_chunks.size(); ++i)
        if (c.done_chunks[i] <= c.done_chunks[i - 1]) throw CheckpointError(path + ": the checkpoint's chunk list is corrupt");
    // The sample count must be what the listed chunks hold.
    std::uint64_t spp = 0;
    for (std::uint64_t k : c.done_chunks) {
        if (c.plan.total_samples && k >= c.plan.chunk_count())
            throw CheckpointError(path + ": the checkpoint lists a chunk outside its render");
        spp += c.plan.chunk(k).samples;
    }
    if (spp != h.samples_per_pixel) throw CheckpointError(path + ": the checkpoint's sample count does not match its chunks");
    return c;
}

}  // namespace clpath
