#include "render/device_exact_film.hpp"

#include <bit>

#include "util/error.hpp"

namespace clpath {

std::vector<std::pair<std::string, std::size_t>> DeviceExactFilm::memory_needs(int width, int height,
                                                                             bool with_half) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    std::vector<std::pair<std::string, std::size_t>> needs{{"exact film", pixels * 3 * sizeof(Fixed128)}};
    if (with_half) needs.emplace_back("exact half film", pixels * sizeof(Fixed128));
    return needs;
}

DeviceExactFilm::DeviceExactFilm(Context& ctx, int width, int height, bool with_half)
    : ctx_(ctx), width_(width), height_(height) {
    const auto needs = memory_needs(width, height, with_half);
    ctx.check_fits(needs);
    sums_ = ctx.buffer(needs[0].second, CL_MEM_READ_WRITE, "exact film");
    error_ = ctx.buffer(sizeof(cl_uint), CL_MEM_READ_WRITE, "exact film error");
    ctx.zero(sums_);
    ctx.zero(error_);
    if (with_half) {
        half_ = ctx.buffer(needs[1].second, CL_MEM_READ_WRITE, "exact half film");
        ctx.zero(half_);
    }
}

void DeviceExactFilm::add_chunk(Film& chunk, Kernel& add_exact, std::uint32_t samples, Kernel* add_exact_half) {
    if (chunk.width() != width_ || chunk.height() != height_)
        throw Error("internal: a chunk film of another size added to a device exact film");
    const std::uint32_t pixels = chunk.pixel_count();
    if (has_half() != (add_exact_half != nullptr))
        throw Error("internal: a half film's chunk added without its kernel, or the other way round");
    if (add_exact_half) {
        add_exact_half->arg(0, chunk.accumulation_buffer()).arg(1, pixels).arg(2, half_).arg(3, error_);
        ctx_.launch(*add_exact_half, pixels, 0);
    }
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
    if (has_half()) {
        f.half().assign(std::size_t(width_) * std::size_t(height_), 0);
        ctx_.read(half_, f.half().data(), f.half().size() * sizeof(Fixed128));
    }
    f.set_samples_per_pixel(samples_);
    return f;
}

}  // namespace clpath
