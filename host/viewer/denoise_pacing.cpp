#include "viewer/denoise_pacing.hpp"

#include <algorithm>

namespace clpath::viewer {

bool DenoisePacing::due(double now, std::uint64_t spp, bool final) const {
    if (busy_ || spp == 0) return false;
    if (last_spp_ == 0) return true;  // nothing shown yet for this estimate
    if (spp <= last_spp_) return false;
    const double wait = std::max(kMinIntervalSeconds, kIntervalPerDenoiseTime * last_seconds_);
    if (now - last_finished_ < wait) return false;
    return final || double(spp) >= kSampleGrowth * double(last_spp_);
}

void DenoisePacing::started(std::uint64_t spp) {
    busy_ = true;
    last_spp_ = spp;
}

void DenoisePacing::finished(double now, double seconds) {
    busy_ = false;
    last_finished_ = now;
    last_seconds_ = seconds;
}

}  // namespace clpath::viewer
