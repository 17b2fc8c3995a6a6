#pragma once
// Progress of a render on stderr: a bar redrawn in place on a terminal, plain
// lines otherwise (logs and CI), at every tenth and at least every 10 s: a
// watchdog thread writes the line when one pass of samples takes longer.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace clpath {

class Progress {
public:
    // target_spp 0 when only a time limit is set; time_limit 0 when none.
    // log_interval: the longest gap between plain lines, in seconds.
    Progress(std::uint64_t target_spp, double time_limit, bool enabled, double log_interval = 10.0);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void update(std::uint64_t spp, double elapsed);
    void finish();

private:
    double fraction(std::uint64_t spp, double elapsed) const;
    void print_line(std::uint64_t spp, double elapsed);  // mutex_ held
    void watch();

    std::uint64_t target_spp_;
    double time_limit_, log_interval_;
    bool enabled_, tty_;
    int last_tenth_ = -1;
    std::chrono::steady_clock::time_point start_, last_draw_{};
    double last_line_ = 0;
    std::uint64_t spp_ = 0;
    std::mutex mutex_;
    std::condition_variable stop_cv_;
    bool stop_ = false, finished_ = false;
    std::thread watchdog_;
};

}  // namespace clpath
