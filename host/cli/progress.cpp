#include "cli/progress.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <unistd.h>

namespace clpath {

Progress::Progress(std::uint64_t target_spp, double time_limit, bool enabled, ProgressOptions options)
    : target_spp_(target_spp), time_limit_(time_limit), o_(std::move(options)), enabled_(enabled) {
    tty_ = o_.tty >= 0 ? o_.tty != 0 : ::isatty(::fileno(o_.out)) != 0;
    if (!o_.clock) {
        const auto start = std::chrono::steady_clock::now();
        o_.clock = [start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    }
    if (enabled_ && !tty_ && o_.watchdog) watchdog_ = std::thread([this] { watch(); });
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
        std::fprintf(o_.out, "progress: %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s\n", int(f * 100),
                     (unsigned long long)spp, elapsed, eta);
    else  // nothing done yet to estimate from
        std::fprintf(o_.out, "progress:   0%%  %llu spp  %.1f s elapsed  ETA not known yet\n",
                     (unsigned long long)spp, elapsed);
    std::fflush(o_.out);
}

void Progress::update(std::uint64_t spp) {
    if (!enabled_) return;
    const double elapsed = o_.clock();
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
        std::fprintf(o_.out, "\r[%s] %3d%%  %llu spp  %.1f s elapsed  ETA %.1f s   ", bar.c_str(), int(f * 100),
                     (unsigned long long)spp, elapsed, eta);
        std::fflush(o_.out);
    } else if (int(f * 10) != last_tenth_) {
        print_line(spp, elapsed);
    }
}

// The elapsed time is the clock's own: the render loop may be inside a long
// pass, with the last count of samples still the latest there is.
double Progress::tick() {
    if (!enabled_ || tty_) return o_.log_interval;
    const double elapsed = o_.clock();
    std::lock_guard<std::mutex> lock(mutex_);
    if (elapsed - last_line_ >= o_.log_interval) print_line(spp_, elapsed);
    return last_line_ + o_.log_interval - elapsed;
}

// Sleeps until the next line falls due rather than polling: a line is then
// late only by the time the thread takes to be woken, not by a polling period.
// A tenth's line printed meanwhile moves the due time on; the watchdog then
// wakes early, finds nothing due and sleeps again.
void Progress::watch() {
    for (;;) {
        const double wait = std::max(tick(), 0.0);
        std::unique_lock<std::mutex> lock(mutex_);
        // Rounded up, so that it never wakes just before the due time and spins.
        const auto d = std::chrono::microseconds(static_cast<long long>(std::ceil(wait * 1e6)) + 1);
        if (stop_cv_.wait_for(lock, d, [this] { return stop_; })) return;
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
    if (enabled_ && tty_ && !finished_) std::fprintf(o_.out, "\n");
    finished_ = true;
}

}  // namespace clpath
