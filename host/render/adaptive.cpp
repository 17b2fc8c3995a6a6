#include "render/adaptive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/error.hpp"

namespace clpath {

std::uint64_t adaptive_min_samples(double noise_target) {
    if (!(noise_target > 0)) throw Error("internal: a noise target must be positive");
    return std::max<std::uint64_t>(16, std::uint64_t(std::ceil(4.0 / std::sqrt(noise_target))));
}

double adaptive_pixel_error(const ExactFilm& film, std::size_t pixel) {
    const std::uint64_t n = film.samples_of(pixel);
    if (n < 2 || film.half().empty()) return std::numeric_limits<double>::infinity();
    // Whole chunks of even length from even indices: half the samples are odd.
    const double full = (fixed_to_double(film.sums()[pixel * 3]) + fixed_to_double(film.sums()[pixel * 3 + 1]) +
                         fixed_to_double(film.sums()[pixel * 3 + 2])) /
                        double(n);
    const double half = fixed_to_double(film.half()[pixel]) / double(n / 2);
    return std::abs(full - half) / (1e-4 + std::sqrt(std::max(full, 0.0)));
}

std::vector<std::uint8_t> adaptive_active_pixels(const ExactFilm& film, double noise_target,
                                                 std::uint64_t min_samples) {
    const int w = film.width(), h = film.height();
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    if (film.half().size() != pixels) throw Error("internal: adaptive sampling needs the film's half film");
    std::vector<std::uint8_t> unconverged(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        unconverged[p] = film.samples_of(p) < min_samples || !(adaptive_pixel_error(film, p) < noise_target);
    std::vector<std::uint8_t> active(pixels, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool any = false;
            for (int dy = -1; dy <= 1 && !any; ++dy)
                for (int dx = -1; dx <= 1 && !any; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx >= 0 && ny >= 0 && nx < w && ny < h) any = unconverged[std::size_t(ny) * w + nx];
                }
            active[std::size_t(y) * w + x] = any;
        }
    return active;
}

}  // namespace clpath
