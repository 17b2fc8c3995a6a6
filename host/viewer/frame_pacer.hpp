#pragma once
// How many samples per pixel the next frame adds, so that rendering fills the
// frame budget without exceeding it: measured seconds per sample per pixel
// (smoothed), never fewer than one sample (the renderer adds whole samples).
#include <cstdint>

namespace clpath::viewer {

class FramePacer {
public:
    explicit FramePacer(double budget_seconds) : budget_(budget_seconds) {}

    std::uint32_t next_samples() const;
    // samples were added in seconds of rendering.
    void record(std::uint32_t samples, double seconds);
    // The resolution or the scene changed: earlier timings no longer apply.
    void forget() { seconds_per_sample_ = 0; }

    double budget() const { return budget_; }

private:
    // More in one frame would leave the image frozen for long after a camera move.
    static constexpr std::uint32_t kMaxSamplesPerFrame = 1024;
    double budget_;
    double seconds_per_sample_ = 0;
};

}  // namespace clpath::viewer
