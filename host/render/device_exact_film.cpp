#include "render/device_exact_film.hpp"

#include <bit>

#include "util/error.hpp"

namespace clpath {

std::vector<std::pair<std::string, std::size_t>> DeviceExactFilm::memory_needs(int width, int height) {
    return {{"exact film", std::size_t(width) * std::size_t(height) * 3 * sizeof(Fixed128)}};
}

DeviceExactFilm::DeviceExactFilm(Context& ctx, int width, int height) : ctx_(ctx), width_(width), height_(height) {
    ctx.check_fits(memory_needs(width, height));
    sums_ = ctx.buffer(memory_needs(width, height)[0].second, CL_MEM_READ_WRITE, "exact film");
    error_ = ctx.buffer(sizeof(cl_uint), CL_MEM_READ_WRITE, "exact film error");
    ctx.zero(sums_);
    ctx.zero(error_);
}

void DeviceExactFilm::add_chunk(Film& chunk, Kernel& add_exact, std::uint32_t samples) {
    if (chunk.width() != width_ || chunk.height() != height_)
        throw Error("internal: a chunk film of another size added to a device exact film");
    const std::uint32_t pixels = chunk.pixel_count();
    add_exact.arg(0, chunk.accumulation_buffer()).arg(1, pixels).arg(2, sums_).arg(3, error_);
    ctx_.launch(add_exact, pixels, 0);
    samples_ += samples;
}

ExactFilm DeviceExactFilm::read() const {
    cl_uint error = 0;
    ctx_.read(error_, &error, sizeof error);
    if (error & 1u) throw Error("a film sum is not finite");
    if (error & 2u) throw Error("a film sum is too large to accumulate exactly (2^63 or more)");
    ExactFilm f(width_, height_);
    // The device's ulong2 (low, high) is the host's little-endian __int128.
    static_assert(sizeof(Fixed128) == 16 && std::endian::native == std::endian::little);
    ctx_.read(sums_, f.sums().data(), f.sums().size() * sizeof(Fixed128));
    f.set_samples_per_pixel(samples_);
    return f;
}

}  // namespace clpath
