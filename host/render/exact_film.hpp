#pragma once
// Order-independent image sums, so that a render split over devices, processes
// and machines gives the same bits as a render on one device.
//
// Floating-point addition is not associative: two devices that each sum half
// of the sample chunks, merged, would differ in the last bits from one device
// that summed them all. Here every chunk's per-pixel float sum is converted
// exactly into a signed 128-bit fixed-point integer (2^-64 resolution, range
// ±2^63) and integers are added, which is associative and commutative. The
// total is then the same whatever device or rank rendered which chunk, and in
// whatever order chunks were merged. The same idea as the "reproducible
// summation" of Demmel and Nguyen (2015) and the long accumulators of
// Kulisch, at a fixed precision chosen far below float resolution.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "shared_structs.h"

namespace clpath {

using Fixed128 = __int128;

// fixed = f * 2^64, exactly for |f| in [2^-41, 2^63) (a float's 24 mantissa
// bits then land on whole fixed-point units); smaller magnitudes are
// truncated towards zero, deterministically. Throws clpath::Error for
// non-finite values and for |f| >= 2^63.
Fixed128 to_fixed(float f);
double fixed_to_double(Fixed128 v);

class ExactFilm {
public:
    ExactFilm() = default;
    ExactFilm(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    std::uint64_t samples_per_pixel() const { return samples_; }
    // 3 values (R, G, B) per pixel, row 0 at the top.
    const std::vector<Fixed128>& sums() const { return sums_; }
    std::vector<Fixed128>& sums() { return sums_; }

    // Adds one chunk of `samples` samples per pixel: the device film's
    // compensated running sums (value = sum - comp), one AccumPixel a pixel.
    void add_chunk(const std::vector<AccumPixel>& film, std::uint32_t samples);
    // Adds another partial total (from another device or rank), half film included.
    void add(const ExactFilm& other);
    void set_samples_per_pixel(std::uint64_t spp) { samples_ = spp; }

    // Adaptive sampling (render/adaptive.hpp). The half film: per pixel the
    // sum of r+g+b over its odd-indexed samples; empty without adaptive sampling.
    const std::vector<Fixed128>& half() const { return half_; }
    std::vector<Fixed128>& half() { return half_; }
    // Each pixel's own sample count, row 0 at the top; empty when every pixel
    // holds samples_per_pixel() samples. Kept by the host (the kernels never
    // count): the adaptive schedule decides it.
    const std::vector<std::uint32_t>& pixel_samples() const { return pixel_samples_; }
    void set_pixel_samples(std::vector<std::uint32_t> counts);
    // A pixel's sample count, whichever way it is kept.
    std::uint64_t samples_of(std::size_t pixel) const {
        return pixel_samples_.empty() ? samples_ : pixel_samples_[pixel];
    }

    // The mean radiance, each pixel's sum divided by its sample count (0 where it has none).
    Image mean() const;

private:
    int width_ = 0, height_ = 0;
    std::uint64_t samples_ = 0;
    std::vector<Fixed128> sums_;
    std::vector<Fixed128> half_;
    std::vector<std::uint32_t> pixel_samples_;
};

}  // namespace clpath
