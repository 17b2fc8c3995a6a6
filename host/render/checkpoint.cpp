#include "render/checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/error.hpp"

namespace clpath {
namespace {

constexpr char kMagic[8] = {'C', 'L', 'P', 'C', 'K', 'P', 'T', '1'};
// An adaptive render's: the header is followed by the noise target (a
// double), and the sums by the half film and the per-pixel counts.
constexpr char kMagicAdaptive[8] = {'C', 'L', 'P', 'C', 'K', 'P', 'A', '1'};

struct Header {
    char magic[8];
    std::uint64_t render_hash;
    std::uint64_t total_samples;
    std::uint64_t chunk_samples;
    std::uint64_t samples_per_pixel;
    std::uint64_t width, height;
    std::uint64_t done_count;
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
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw Error(path + ": cannot write the checkpoint (" + std::strerror(errno) + ")");
        f.write(reinterpret_cast<const char*>(&h), sizeof h);
        if (adaptive) f.write(reinterpret_cast<const char*>(&c.noise_target), sizeof c.noise_target);
        f.write(reinterpret_cast<const char*>(c.done_chunks.data()), std::streamsize(c.done_chunks.size() * 8));
        f.write(reinterpret_cast<const char*>(c.film.sums().data()),
                std::streamsize(c.film.sums().size() * sizeof(Fixed128)));
        if (adaptive) {
            f.write(reinterpret_cast<const char*>(c.film.half().data()), std::streamsize(pixels * sizeof(Fixed128)));
            f.write(reinterpret_cast<const char*>(c.film.pixel_samples().data()),
                    std::streamsize(pixels * sizeof(std::uint32_t)));
        }
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
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot open the checkpoint (" + std::strerror(errno) + ")");
    Header h{};
    f.read(reinterpret_cast<char*>(&h), sizeof h);
    const bool adaptive = f && std::memcmp(h.magic, kMagicAdaptive, sizeof kMagic) == 0;
    if (!f || (!adaptive && std::memcmp(h.magic, kMagic, sizeof kMagic) != 0))
        throw Error(path + ": not a clpath checkpoint");
    if (h.width == 0 || h.height == 0 || h.width > 16384 || h.height > 16384 || h.chunk_samples == 0 ||
        h.chunk_samples > 0xffffffffull || h.done_count > (1ull << 32))
        throw Error(path + ": the checkpoint's header is corrupt");
    Checkpoint c;
    if (adaptive) {
        f.read(reinterpret_cast<char*>(&c.noise_target), sizeof c.noise_target);
        if (!f) throw Error(path + ": the checkpoint is truncated");
        if (!(c.noise_target > 0) || !std::isfinite(c.noise_target))
            throw Error(path + ": the checkpoint's noise target is corrupt");
    }
    c.render_hash = h.render_hash;
    c.plan.total_samples = h.total_samples;
    c.plan.chunk_samples = std::uint32_t(h.chunk_samples);
    c.done_chunks.resize(h.done_count);
    f.read(reinterpret_cast<char*>(c.done_chunks.data()), std::streamsize(h.done_count * 8));
    c.film = ExactFilm(int(h.width), int(h.height));
    f.read(reinterpret_cast<char*>(c.film.sums().data()), std::streamsize(c.film.sums().size() * sizeof(Fixed128)));
    if (adaptive) {
        const std::size_t pixels = std::size_t(h.width) * std::size_t(h.height);
        c.film.half().assign(pixels, 0);
        f.read(reinterpret_cast<char*>(c.film.half().data()), std::streamsize(pixels * sizeof(Fixed128)));
        std::vector<std::uint32_t> counts(pixels);
        f.read(reinterpret_cast<char*>(counts.data()), std::streamsize(pixels * sizeof(std::uint32_t)));
        for (std::uint32_t n : counts)
            if (n > h.samples_per_pixel) throw Error(path + ": the checkpoint's sample counts are corrupt");
        c.film.set_pixel_samples(std::move(counts));
    }
    if (!f) throw Error(path + ": the checkpoint is truncated");
    f.peek();
    if (!f.eof()) throw Error(path + ": the checkpoint has trailing bytes");
    c.film.set_samples_per_pixel(h.samples_per_pixel);
    for (std::size_t i = 1; i < c.done_chunks.size(); ++i)
        if (c.done_chunks[i] <= c.done_chunks[i - 1]) throw Error(path + ": the checkpoint's chunk list is corrupt");
    // The sample count must be what the listed chunks hold.
    std::uint64_t spp = 0;
    for (std::uint64_t k : c.done_chunks) {
        if (c.plan.total_samples && k >= c.plan.chunk_count())
            throw Error(path + ": the checkpoint lists a chunk outside its render");
        spp += c.plan.chunk(k).samples;
    }
    if (spp != h.samples_per_pixel) throw Error(path + ": the checkpoint's sample count does not match its chunks");
    return c;
}

}  // namespace clpath
