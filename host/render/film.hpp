#pragma once
// The film: per pixel a Kahan-compensated running sum of radiance samples
// (AccumPixel, kernels/shared_structs.h), the number of samples every pixel
// holds, and the resolve into a displayable image. Its raw state can be read
// and written exactly, for checkpoints and for merging films made elsewhere.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cl/context.hpp"
#include "image/image.hpp"
#include "shared_structs.h"

namespace clpath {

// Largest samples-per-pixel count one film may hold: the kernels index
// samples with 32-bit integers.
constexpr std::uint64_t kMaxSamplesPerPixel = 0xffffffffull;

// A film's contents, bit for bit.
struct FilmState {
    int width = 0, height = 0;
    std::uint64_t samples_per_pixel = 0;
    std::vector<AccumPixel> pixels;  // width * height, row 0 at the top: sum and compensation
};

class Film {
public:
    // A cleared film (no samples). Throws clpath::Error when it does not fit on the device.
    Film(Context& ctx, int width, int height);

    // The buffers a film of this size needs on a device, by name (for Context::check_fits).
    static std::vector<std::pair<std::string, std::size_t>> memory_needs(int width, int height);

    Context& context() const { return ctx_; }
    int width() const { return width_; }
    int height() const { return height_; }
    std::uint32_t pixel_count() const { return std::uint32_t(width_) * std::uint32_t(height_); }
    std::uint64_t samples_per_pixel() const { return samples_per_pixel_; }

    // Back to no samples.
    void clear();
    // An empty film (new, or emptied by DeviceExactFilm::add_chunk) that
    // takes samples from the index first_sample on: a chunk of a chunked
    // render. Touches no device memory.
    void start_chunk_at(std::uint64_t first_sample);
    // Records that the kernels have added n samples to every pixel. The
    // integrator's launches call it; the sample index of the next launch starts here.
    void count_samples(std::uint32_t n);

    // The raw sums, compensations and sample count (a blocking read).
    FilmState read_state() const;
    // Replaces the film's contents; the state must have the film's size and a
    // sample count within kMaxSamplesPerPixel (else clpath::Error).
    void write_state(const FilmState& state);

    // Resolves the mean, times exposure, into linear_buffer() (RGBA float) and
    // srgb_buffer() (RGBA8, row 0 at the top) with the integrator program's
    // film_resolve kernel; left on the device for a viewer that shares them with OpenGL.
    void resolve_on_device(Kernel& resolve, float exposure);
    // What resolve_on_device left, read back.
    RenderedImage read_image() const;

    const Buffer& accumulation_buffer() const { return accum_; }
    const Buffer& linear_buffer() const { return linear_; }
    const Buffer& srgb_buffer() const { return srgb_; }

private:
    Context& ctx_;
    int width_, height_;
    std::uint64_t samples_per_pixel_ = 0;
    Buffer accum_, linear_, srgb_;
};

}  // namespace clpath
