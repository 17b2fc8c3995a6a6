#include "render/environment_map.hpp"

#include <cmath>

#include "image/image.hpp"
#include "render/light_table.hpp"
#include "util/error.hpp"

namespace clpath {

EnvironmentMap load_environment_map(const Environment& e) {
    EnvironmentMap m;
    if (e.image.empty()) {
        m.pixels.assign(4, 0.0f);
        m.cdf = {CLP_ENV_NOT_SAMPLED};
        m.average_radiance = luminance(e.color);
        return m;
    }
    const Image img = read_image(e.image);
    if (img.width < 1 || img.height < 1) throw Error(e.image + ": empty environment image");
    m.width = img.width;
    m.height = img.height;
    const std::size_t w = std::size_t(img.width), h = std::size_t(img.height);
    m.pixels.resize(w * h * 4);
    std::vector<double> f(w * h);
    double total = 0, solid_angle = 0;
    for (std::size_t y = 0; y < h; ++y) {
        const double sin_theta = std::sin(M_PI * (double(y) + 0.5) / double(h));
        for (std::size_t x = 0; x < w; ++x) {
            glm::vec3 c;
            for (int k = 0; k < 3; ++k) {
                float v = img.rgb[(y * w + x) * 3 + k];
                if (!std::isfinite(v))
                    throw Error(e.image + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                ") is not finite");
                // Lossy EXR compression (DWA, as in Blender's studio lights)
                // and resampling filters ring slightly below zero; a radiance
                // cannot be negative, so such texels are black.
                if (v < 0) {
                    v = 0;
                    ++m.negative_values;
                }
                c[k] = v;
                m.pixels[(y * w + x) * 4 + k] = v;
            }
            m.pixels[(y * w + x) * 4 + 3] = 1.0f;
            f[y * w + x] = luminance(c) * sin_theta;
            total += f[y * w + x];
            solid_angle += sin_theta;
        }
    }
    m.average_radiance = solid_angle > 0 ? total / solid_angle * e.scale : 0;
    if (!e.importance_sampled || !(total > 0)) {
        m.cdf = {CLP_ENV_NOT_SAMPLED};
        return m;
    }
    // CDFs in double, stored as float; the last entry is exactly 1.
    m.cdf.assign(CLP_ENV_CDF_SIZE(w, h), 0.0f);
    std::vector<double> row_sum(h, 0.0);
    for (std::size_t y = 0; y < h; ++y) {
        float* row = &m.cdf[CLP_ENV_ROW_CDF(w, h, y)];
        double acc = 0;
        for (std::size_t x = 0; x < w; ++x) acc += f[y * w + x];
        row_sum[y] = acc;
        double run = 0;
        for (std::size_t x = 0; x < w; ++x) {
            run += f[y * w + x];
            // A black row is sampled uniformly; the marginal never picks it anyway.
            row[x + 1] = float(acc > 0 ? run / acc : double(x + 1) / double(w));
        }
        row[w] = 1.0f;
    }
    double run = 0;
    for (std::size_t y = 0; y < h; ++y) {
        run += row_sum[y];
        m.cdf[y + 1] = float(run / total);
    }
    m.cdf[h] = 1.0f;
    return m;
}

}  // namespace clpath
