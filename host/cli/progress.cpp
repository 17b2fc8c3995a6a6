#include "cli/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace clpath {

Progress::Progress(std::uint64_t target_spp, double time_limit, bool enabled)
    : target_spp_(target_spp), time_limit_(time_limit), enabled_(enabled), tty_(::isatty(2)) {}

void Progress::update(std::uint64_t spp, double elapsed) {
    if (!enabled_) return;
    double f = 0;
    if (target_spp_) f = double(spp) / double(target_spp_);
    if (time_limit_ > 0) f = std::max(f, elapsed / time_limit_);
    f = std::clamp(f, 0.0, 1.0);
    const double eta = f > 0 ? elapsed * (1 - f) / f : 0;
    if (tty_) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_draw_ < std::chrono::milliseconds(100) && f < 1) return;
        last_draw_ = now;
        const int width = 30, filled = int(f * width);
        std::string bar(filled, '#');
        bar.resize(width, '.');
        std::fprintf(stderr, "\r[%s] %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s   ", bar.c_str(), int(f * 100),
                     (unsigned long long)spp, elapsed, eta);
    } else {
        const int tenth = int(f * 10);
        if (tenth == last_tenth_) return;
        last_tenth_ = tenth;
        std::fprintf(stderr, "progress: %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s\n", tenth * 10,
                     (unsigned long long)spp, elapsed, eta);
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (enabled_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace clpath
