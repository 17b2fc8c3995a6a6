#pragma once
// Progress of a render on stderr: a bar redrawn in place on a terminal, plain
// lines otherwise (logs and CI): one at every tenth, and at least one every
// log interval (default 10 s): a watchdog thread writes a line when that long
// has passed since the last, even while the render loop is stuck in one long
// pass.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <thread>

namespace clpath {

// The longest gap between plain lines, unless the caller asks for another
// (the render command takes CLPATH_PROGRESS_INTERVAL_MS).
inline constexpr double kDefaultProgressInterval = 10.0;

struct ProgressOptions {
    double log_interval = kDefaultProgressInterval;  // seconds
    // Seconds since the render started; default: a steady clock started with the Progress.
    std::function<double()> clock;
    std::FILE* out = stderr;
    int tty = -1;          // -1: ask isatty() about out
    bool watchdog = true;  // false: nobody calls tick() but the owner (tests with a fake clock)
};

class Progress {
public:
    // target_spp 0 when only a time limit is set; time_limit 0 when none.
    Progress(std::uint64_t target_spp, double time_limit, bool enabled, ProgressOptions options = {});
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // The render loop's latest count: a line when it crosses a tenth.
    void update(std::uint64_t spp);
    // The watchdog's check: a line when log_interval has passed since the last
    // line. Returns the seconds until the next line falls due.
    double tick();
    void finish();

private:
    double fraction(std::uint64_t spp, double elapsed) const;
    void print_line(std::uint64_t spp, double elapsed);  // mutex_ held
    void watch();

    std::uint64_t target_spp_;
    double time_limit_;
    ProgressOptions o_;
    bool enabled_, tty_;
    int last_tenth_ = -1;
    std::chrono::steady_clock::time_point last_draw_{};
    double last_line_ = 0;
    std::uint64_t spp_ = 0;
    std::mutex mutex_;
    std::condition_variable stop_cv_;
    bool stop_ = false, finished_ = false;
    std::thread watchdog_;
};

}  // namespace clpath
