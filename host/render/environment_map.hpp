#pragma once
// The environment as the kernels read it: an equirectangular image (or none,
// for a constant colour) and the 2D piecewise-constant distribution that
// importance-samples it (PBR 4th ed., A.5.6), in the layout of kernels/lights.cl.
#include <vector>

#include "scene/scene.hpp"

namespace clpath {

struct EnvironmentMap {
    int width = 0, height = 0;     // 0 x 0 without an image
    std::vector<float> pixels;     // RGBA float, row 0 = straight up; one dummy texel without an image
    // Of luminance x sin(theta), in the layout of CLP_ENV_ROW_CDF; {CLP_ENV_NOT_SAMPLED}:
    // sample the sphere uniformly instead (both in shared_structs.h).
    std::vector<float> cdf;
    double average_radiance = 0;   // mean luminance over the sphere (solid-angle weighted)
    std::size_t negative_values = 0;  // channel values below 0 in the image, read as 0
};

// Reads the image (through OpenImageIO) and builds the distribution; throws
// clpath::Error naming the file when it cannot be read or a value is not
// finite. Negative values (lossy compression's ringing) are read as 0.
EnvironmentMap load_environment_map(const Environment& environment);

}  // namespace clpath
