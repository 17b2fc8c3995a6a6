// The progress printer's schedule of plain lines (logs, CI), driven by a fake
// clock: no test here waits for real time to pass.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <string>
#include <vector>

#include "cli/progress.hpp"

namespace clpath {
namespace {

// A Progress writing plain lines to a temporary file, at the fake time *now.
struct FakeLog {
    double now = 0;
    std::FILE* file = std::tmpfile();
    ~FakeLog() { std::fclose(file); }

    ProgressOptions options(double interval) {
        ProgressOptions o;
        o.log_interval = interval;
        o.clock = [this] { return now; };
        o.out = file;
        o.tty = 0;
        o.watchdog = false;  // the test calls tick() where the thread would
        return o;
    }

    // The "elapsed" time of every line written so far.
    std::vector<double> stamps() {
        std::fflush(file);
        std::rewind(file);
        std::string text;
        char buf[4096];
        for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file)) > 0;) text.append(buf, n);
        std::vector<double> t;
        static const std::regex line(R"(progress: +[0-9]+%  [0-9]+ spp  ([0-9.]+) s elapsed)");
        for (std::sregex_iterator it(text.begin(), text.end(), line), end; it != end; ++it)
            t.push_back(std::stod((*it)[1]));
        return t;
    }
};

// Lines print the elapsed time to 0.1 s: a gap read from two of them is off by
// up to two roundings of 0.05 s (and the fake thread's 1 us wake margins).
constexpr double kStampError = 0.1 + 1e-4;

double largest_gap(const std::vector<double>& t, double end) {
    double gap = 0, last = 0;
    for (double x : t) gap = std::max(gap, x - last), last = x;
    return std::max(gap, end - last);
}

// The watchdog thread's loop with a fake clock: sleep for what tick() says,
// woken `late` seconds after that; the render loop reports its count every
// `poll` seconds.
void run_watchdog(FakeLog& log, Progress& p, double seconds, double late, double poll,
                  std::uint64_t spp_per_poll) {
    double next_tick = 0, next_poll = 0;
    std::uint64_t spp = 0;
    while (log.now < seconds) {
        log.now = std::min(next_tick, next_poll);
        if (log.now >= seconds) break;
        if (log.now == next_poll) {
            p.update(spp);
            spp += spp_per_poll;
            next_poll += poll;
        }
        // Like the thread, never sleeping for nothing: at least 1 us.
        if (log.now == next_tick) next_tick = log.now + std::max(p.tick(), 0.0) + late + 1e-6;
    }
}

TEST(Progress, DefaultIntervalIsTenSeconds) {
    EXPECT_EQ(ProgressOptions{}.log_interval, 10.0);
    EXPECT_EQ(kDefaultProgressInterval, 10.0);
    FakeLog log;
    ProgressOptions o = log.options(0);
    o.log_interval = ProgressOptions{}.log_interval;
    Progress p(1000, 0, true, o);
    p.update(0);  // the first count always gets its line
    ASSERT_EQ(log.stamps().size(), 1u);
    log.now = 9.99;
    EXPECT_NEAR(p.tick(), 0.01, 1e-9);  // due in 10 ms
    EXPECT_EQ(log.stamps().size(), 1u);
    log.now = 10.0;
    p.tick();
    EXPECT_EQ(log.stamps(), (std::vector<double>{0.0, 10.0}));
    log.now = 19.9;
    EXPECT_NEAR(p.tick(), 0.1, 1e-9);
    log.now = 20.0;
    p.tick();
    EXPECT_EQ(log.stamps(), (std::vector<double>{0.0, 10.0, 20.0}));
}

// A render stuck in one long pass (no new samples for 95 s): the watchdog
// alone keeps the lines coming, one exactly every interval when it wakes on
// time, one interval plus its lateness when it does not.
TEST(Progress, WatchdogWritesALineEveryIntervalDuringALongPass) {
    for (double late : {0.0, 0.5}) {
        FakeLog log;
        Progress p(1000, 0, true, log.options(10.0));
        run_watchdog(log, p, 95, late, 0.25, 0);
        const auto t = log.stamps();
        ASSERT_EQ(t.size(), 10u) << "late " << late;  // 0, then 10 + late apart
        for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], 10.0 + late, kStampError);
    }
}

// Tenths and the interval together: a line at every tenth, and never a gap
// longer than the interval (the watchdog waits for the due time of the last
// line, whoever printed it).
TEST(Progress, TenthsAndIntervalLinesInterleave) {
    FakeLog log;
    Progress p(1000, 0, true, log.options(2.0));
    // 1000 samples in 25 s: a tenth every 2.5 s, longer than the interval.
    run_watchdog(log, p, 25.2, 0, 0.05, 2);
    const auto t = log.stamps();
    EXPECT_LE(largest_gap(t, 25.2), 2.0 + kStampError);
    EXPECT_GE(t.size(), 13u);  // 11 tenths, plus the interval's lines between them
}

// The control: the same long pass with nobody calling tick() (no watchdog)
// leaves a gap the checks above would reject.
TEST(Progress, WithoutTheWatchdogALongPassIsSilent) {
    FakeLog log;
    Progress p(1000, 0, true, log.options(10.0));
    for (; log.now < 95; log.now += 0.25) p.update(0);
    const auto t = log.stamps();
    EXPECT_EQ(t.size(), 1u);
    EXPECT_GT(largest_gap(t, 95), 10.0);
}

TEST(Progress, TimeLimitTenths) {
    FakeLog log;
    Progress p(0, 20.0, true, log.options(100.0));
    for (; log.now <= 20.0; log.now += 0.5) p.update(0);
    // 0%, then a tenth every 2 s.
    EXPECT_EQ(log.stamps().size(), 11u);
}

TEST(Progress, TerminalGetsNoPlainLines) {
    FakeLog log;
    ProgressOptions o = log.options(1.0);
    o.tty = 1;
    Progress p(10, 0, true, o);
    log.now = 50;
    p.tick();
    EXPECT_TRUE(log.stamps().empty());
}

TEST(Progress, DisabledWritesNothing) {
    FakeLog log;
    Progress p(10, 0, false, log.options(1.0));
    p.update(5);
    log.now = 50;
    p.tick();
    EXPECT_TRUE(log.stamps().empty());
}

}  // namespace
}  // namespace clpath
