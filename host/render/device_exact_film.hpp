#pragma once
// The exact film kept on the device: a chunk's float sums are converted into
// 128-bit fixed point and added there (film_add_exact, kernels/film.cl), the
// same arithmetic as the host's ExactFilm, so a render over chunks moves no
// film between host and device until someone asks for the image: a
// checkpoint, a merge with other devices, the end.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cl/context.hpp"
#include "render/exact_film.hpp"
#include "render/film.hpp"

namespace clpath {

class DeviceExactFilm {
public:
    // All zero. Throws clpath::Error when it does not fit on the device.
    // with_half: it also keeps adaptive sampling's half film (the chunk
    // films' w lanes, render/adaptive.hpp).
    DeviceExactFilm(Context& ctx, int width, int height, bool with_half = false);

    // The buffers it needs on a device, by name (for Context::check_fits).
    static std::vector<std::pair<std::string, std::size_t>> memory_needs(int width, int height,
                                                                        bool with_half = false);

    // Enqueues the addition of the chunk film's sums with the program's
    // film_add_exact kernel, which also empties the chunk film; nothing waits.
    // With a half film, add_exact_half (film_add_exact_half) adds the w lanes first.
    void add_chunk(Film& chunk, Kernel& add_exact, std::uint32_t samples, Kernel* add_exact_half = nullptr);
    bool has_half() const { return half_.get() != nullptr; }
    // The sums so far (a blocking read). Throws clpath::Error when a chunk
    // held a sum that is not finite or too large to hold exactly.
    ExactFilm read() const;
    std::uint64_t samples_per_pixel() const { return samples_; }

private:
    Context& ctx_;
    int width_, height_;
    std::uint64_t samples_ = 0;
    Buffer sums_, error_, half_;
};

}  // namespace clpath
