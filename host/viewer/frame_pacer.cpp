#include "viewer/frame_pacer.hpp"

#include <algorithm>

namespace clpath::viewer {

std::uint32_t FramePacer::next_samples() const {
    if (seconds_per_sample_ <= 0) return 1;  // nothing measured yet
    const double n = budget_ / seconds_per_sample_;
    return std::uint32_t(std::clamp(n, 1.0, double(kMaxSamplesPerFrame)));
}

void FramePacer::record(std::uint32_t samples, double seconds) {
    if (samples == 0 || !(seconds > 0)) return;
    const double s = seconds / samples;
    // Smoothed like the renderer's launch sizing: one slow frame (a compile,
    // a busy machine) does not swing the next one.
    seconds_per_sample_ = seconds_per_sample_ > 0 ? 0.7 * seconds_per_sample_ + 0.3 * s : s;
}

}  // namespace clpath::viewer
