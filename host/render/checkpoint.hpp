#pragma once
// A render's running sums on disk, so that a long render can be stopped and
// continued: the exact film (render/exact_film.hpp), the chunks it holds, and
// what it is a render of (and, for an adaptive render, the half film and
// each pixel's sample count, taken between passes). Continuing adds the missing chunks, and since chunk
// totals add exactly, the final image is the same bits as an uninterrupted
// render of the same seed and sample count.
#include <cstdint>
#include <string>
#include <vector>

#include "render/chunks.hpp"
#include "render/exact_film.hpp"
#include "util/error.hpp"

namespace clpath {

// A checkpoint that cannot be read or does not fit the render: a message
// about the checkpoint's file alone (the caller need not name the scene).
struct CheckpointError : Error {
    using Error::Error;
};

struct Checkpoint {
    std::uint64_t render_hash = 0;  // scene and settings (render/render_hash.hpp)
    ChunkPlan plan;
    std::vector<std::uint64_t> done_chunks;
    ExactFilm film;           // with adaptive sampling, its half film and per-pixel counts too
    double noise_target = 0;  // adaptive sampling's target; 0: none
};

// Written to a temporary file beside path and renamed over it, so a crash
// mid-write leaves the previous checkpoint whole.
void write_checkpoint(const std::string& path, const Checkpoint& checkpoint);
// The file holds a header, the finished chunks, the sums and an xxHash (XXH3)
// checksum over all three. Throws clpath::Error naming the file for anything
// unreadable, not a clpath checkpoint, of a size other than its header
// describes (checked before anything is allocated), or whose checksum does
// not match.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace clpath
