#pragma once
// Are two renderers' images equal in distribution? Each side is rendered K
// times with independent seeds; per pixel, the runs give a mean and the
// variance of that mean. Pixels are pooled into blocks, and each block's
// difference is z-tested against its standard error. The significance is
// Sidak-corrected over blocks, so an agreeing pair fails with probability
// alpha in all (after Mitsuba 3's render tests, on blocks rather than pixels
// so that the normal approximation holds at small sample counts).
#include <string>
#include <vector>

#include "image/image.hpp"

namespace clpath::test {

struct Agreement {
    int blocks = 0, failed = 0;
    double worst_z = 0;       // largest |z| over blocks
    int worst_x = 0, worst_y = 0;
    double critical_z = 0;    // the Sidak-corrected threshold
    bool ok() const { return failed == 0; }
    std::string describe() const;
};

Agreement image_agreement(const std::vector<Image>& a, const std::vector<Image>& b, int block = 8,
                          double alpha = 0.01);

}  // namespace clpath::test
