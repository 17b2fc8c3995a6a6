#pragma once
// When the viewer denoises its displayed frame again. The estimate grows every
// frame, but the denoiser is not run every frame: Open Image Denoise takes tens
// of milliseconds to seconds per megapixel on the CPU, and on a CPU OpenCL
// device it competes for the cores that render. Denoising every frame would
// cut the sample rate and the frame rate for images that differ from the last
// by noise the eye cannot see. So a new denoised image is made only when
//   - enough time has passed since the last one finished: at least
//     kMinIntervalSeconds, and kIntervalPerDenoiseTime times the last
//     denoise's own time (the denoiser then takes at most about a fifth of the
//     wall time, however slow it is on this machine and image size), and
//   - the estimate has grown by kSampleGrowth (its noise falls as 1/sqrt(spp):
//     1.25x the samples is 11% less noise), or has stopped growing (--max-spp)
//     with samples the shown image has not seen.
#include <cstdint>

namespace clpath::viewer {

class DenoisePacing {
public:
    static constexpr double kMinIntervalSeconds = 0.25;
    static constexpr double kIntervalPerDenoiseTime = 4;
    static constexpr double kSampleGrowth = 1.25;

    // Whether to start denoising the estimate now (it has spp samples;
    // `final`: it will get no more).
    bool due(double now_seconds, std::uint64_t spp, bool final) const;
    // A denoise of an estimate of spp samples started.
    void started(std::uint64_t spp);
    // It finished at now_seconds, having taken seconds.
    void finished(double now_seconds, double seconds);
    // The estimate restarted (camera, size, view): the next denoise is due at once.
    void reset() { *this = DenoisePacing{}; }

    bool busy() const { return busy_; }
    std::uint64_t last_spp() const { return last_spp_; }

private:
    std::uint64_t last_spp_ = 0;  // 0: nothing denoised since the reset
    double last_finished_ = 0, last_seconds_ = 0;
    bool busy_ = false;
};

}  // namespace clpath::viewer
