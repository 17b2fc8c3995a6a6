#include "cli/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace clpath {

Progress::Progress(std::uint64_t target_spp, double time_limit, bool enabled, double log_interval)
    : target_spp_(target_spp),
      time_limit_(time_limit),
      log_interval_(log_interval),
      enabled_(enabled),
      tty_(::isatty(2)),
      start_(std::chrono::steady_clock::now()) {
    if (enabled_ && !tty_) watchdog_ = std::thread([this] { watch(); });
}

Progress::~Progress() { finish(); }

double Progress::fraction(std::uint64_t spp, double elapsed) const {
    double f = 0;
    if (target_spp_) f = double(spp) / double(target_spp_);
    if (time_limit_ > 0) f = std::max(f, elapsed / time_limit_);
    return std::clamp(f, 0.0, 1.0);
}

void Progress::print_line(std::uint64_t spp, double elapsed) {
    const double f = fraction(spp, elapsed);
    const double eta = f > 0 ? elapsed * (1 - f) / f : 0;
    last_tenth_ = int(f * 10);
    last_line_ = elapsed;
    if (f > 0)
        std::fprintf(stderr, "progress: %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s\n", int(f * 100),
                     (unsigned long long)spp, elapsed, eta);
    else  // nothing done yet to estimate from
        std::fprintf(stderr, "progress:   0%%  %llu spp  %.1f s elapsed  ETA not known yet\n", (unsigned long long)spp,
                     elapsed);
    std::fflush(stderr);
}

void Progress::update(std::uint64_t spp, double elapsed) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    spp_ = spp;
    const double f = fraction(spp, elapsed);
    if (tty_) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_draw_ < std::chrono::milliseconds(100) && f < 1) return;
        last_draw_ = now;
        const double eta = f > 0 ? elapsed * (1 - f) / f : 0;
        const int width = 30, filled = int(f * width);
        std::string bar(filled, '#');
        bar.resize(width, '.');
        std::fprintf(stderr, "\r[%s] %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s   ", bar.c_str(), int(f * 100),
                     (unsigned long long)spp, elapsed, eta);
        std::fflush(stderr);
    } else if (int(f * 10) != last_tenth_ || elapsed - last_line_ >= log_interval_) {
        print_line(spp, elapsed);
    }
}

// The elapsed time is the watchdog's own: the render loop may be inside a
// long pass, with the last count of samples still the latest there is.
void Progress::watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
        stop_cv_.wait_for(lock, std::chrono::milliseconds(250));
        if (stop_) break;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (elapsed - last_line_ >= log_interval_) print_line(spp_, elapsed);
    }
}

void Progress::finish() {
    if (watchdog_.joinable()) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        stop_cv_.notify_all();
        watchdog_.join();
    }
    if (enabled_ && tty_ && !finished_) std::fprintf(stderr, "\n");
    finished_ = true;
}

}  // namespace clpath
