#pragma once
// Progress of a render on stderr: a bar redrawn in place on a terminal, plain
// lines at every tenth otherwise (logs and CI).
#include <chrono>
#include <cstdint>

namespace clpath {

class Progress {
public:
    // target_spp 0 when only a time limit is set; time_limit 0 when none.
    Progress(std::uint64_t target_spp, double time_limit, bool enabled);
    void update(std::uint64_t spp, double elapsed);
    void finish();

private:
    std::uint64_t target_spp_;
    double time_limit_;
    bool enabled_, tty_;
    int last_tenth_ = -1;
    std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace clpath
