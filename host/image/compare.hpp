#pragma once
// Image differences, as pbrt's `imgtool diff` reports them: the numbers the
// convergence benchmark and the statistical tests are built on.
#include <array>
#include <string>

#include "image/image.hpp"

namespace clpath {

struct CompareOptions {
    // Clamp both images to [0, clamp] before comparing (0: no clamp). Emitters
    // seen directly are far brighter than anything else and would dominate the MSE.
    float clamp = 0;
    // Leave out pixels whose reference value (any channel) exceeds this (0: keep all).
    float mask_above = 0;
    // Also leave out pixels within this many pixels (in x and y) of one the
    // mask leaves out: the edges of an emitter, where pixels partly covered by
    // it are far noisier than any other and yet below the threshold.
    int mask_grow = 0;
};

struct ImageComparison {
    std::size_t pixels = 0;     // compared (after masking)
    double mse = 0;             // mean over pixels and channels of (a - b)^2
    double rmse = 0;
    double psnr = 0;            // 10 log10(1 / mse): peak 1 in linear radiance; +inf when equal
    double relmse = 0;          // mean of (a - b)^2 / (b^2 + 1e-2), b the reference (pbrt's relMSE)
    std::array<double, 3> mean_a{}, mean_b{};
    double max_abs_diff = 0;    // largest |a - b| over pixels and channels
    int max_x = 0, max_y = 0;   // where it is
};

// b is the reference. Throws clpath::Error when the sizes differ.
ImageComparison compare_images(const Image& a, const Image& b, const CompareOptions& options = {});

// One line: "rmse=... psnr=... relmse=... mean_a=(r,g,b) mean_b=(...) max_diff=... at (x,y) pixels=N".
std::string describe(const ImageComparison& c);

}  // namespace clpath
