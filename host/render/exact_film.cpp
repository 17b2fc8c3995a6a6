#include "render/exact_film.hpp"

#include <bit>
#include <cmath>

#include "util/error.hpp"

namespace clpath {

Fixed128 to_fixed(float f) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
    const int biased = int((bits >> 23) & 0xffu);
    if (biased == 0xff) throw Error("a film sum is not finite");
    // value = m * 2^(biased - 150) (normal) or m * 2^-149 (subnormal), so the
    // fixed-point value is m shifted left by (biased - 150 + 64).
    const std::uint32_t m = (bits & 0x7fffffu) | (biased ? 0x800000u : 0u);
    const int shift = (biased ? biased : 1) - 150 + 64;
    if (shift + 24 > 127) throw Error("a film sum is too large to accumulate exactly (2^63 or more)");
    Fixed128 v;
    if (shift >= 0)
        v = Fixed128(m) << shift;
    else
        v = shift > -32 ? Fixed128(m >> -shift) : 0;
    return (bits >> 31) ? -v : v;
}

double fixed_to_double(Fixed128 v) {
    // Integer part and fraction separately; deterministic, like every step here.
    const bool neg = v < 0;
    const unsigned __int128 u = neg ? (unsigned __int128)(-v) : (unsigned __int128)v;
    const double hi = double(std::uint64_t(u >> 64));
    const double lo = std::ldexp(double(std::uint64_t(u)), -64);
    const double r = hi + lo;
    return neg ? -r : r;
}

ExactFilm::ExactFilm(int width, int height)
    : width_(width), height_(height), sums_(std::size_t(width) * std::size_t(height) * 3, 0) {}

void ExactFilm::add_chunk(const std::vector<AccumPixel>& film, std::uint32_t samples) {
    if (film.size() * 3 != sums_.size())
        throw Error("internal: a chunk film of " + std::to_string(film.size()) + " pixels added to an image of " +
                    std::to_string(sums_.size() / 3));
    for (std::size_t i = 0; i < film.size(); ++i)
        for (int c = 0; c < 3; ++c) sums_[i * 3 + c] += to_fixed(film[i].sum[c]) - to_fixed(film[i].comp[c]);
    samples_ += samples;
}

void ExactFilm::add(const ExactFilm& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw Error("internal: partial images of different sizes cannot be merged");
    for (std::size_t i = 0; i < sums_.size(); ++i) sums_[i] += other.sums_[i];
    if (!other.half_.empty()) {
        if (half_.empty()) half_.assign(other.half_.size(), 0);
        for (std::size_t i = 0; i < half_.size(); ++i) half_[i] += other.half_[i];
    }
    samples_ += other.samples_;
}

void ExactFilm::set_pixel_samples(std::vector<std::uint32_t> counts) {
    if (!counts.empty() && counts.size() != std::size_t(width_) * std::size_t(height_))
        throw Error("internal: per-pixel sample counts of another size than the film");
    pixel_samples_ = std::move(counts);
}

Image ExactFilm::mean() const {
    Image img;
    img.width = width_;
    img.height = height_;
    img.rgb.resize(sums_.size());
    const double inv = samples_ ? 1.0 / double(samples_) : 0.0;
    if (pixel_samples_.empty()) {
        for (std::size_t i = 0; i < sums_.size(); ++i) img.rgb[i] = float(fixed_to_double(sums_[i]) * inv);
        return img;
    }
    for (std::size_t p = 0; p < pixel_samples_.size(); ++p) {
        const double inv_p = pixel_samples_[p] ? 1.0 / double(pixel_samples_[p]) : 0.0;
        for (std::size_t c = 0; c < 3; ++c) img.rgb[p * 3 + c] = float(fixed_to_double(sums_[p * 3 + c]) * inv_p);
    }
    return img;
}

}  // namespace clpath
