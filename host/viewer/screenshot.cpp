#include "viewer/screenshot.hpp"

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "image/image.hpp"
#include "image/tone_map.hpp"
#include "util/error.hpp"
#include "viewer/gl.hpp"

namespace clpath::viewer {
namespace {

// A scene named by a path ("scenes/x.json") still gives a plain file name.
std::string file_stem(const std::string& name) {
    std::string s = std::filesystem::path(name).stem().string();
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
    return s.empty() ? "scene" : s;
}

}  // namespace

std::string screenshot_stem(const std::string& scene, const std::string& integrator, std::uint64_t spp) {
    return file_stem(scene) + (integrator == "path" ? "" : "-" + integrator) + "-" + std::to_string(spp) + "spp";
}

std::vector<std::string> save_screenshot(Renderer& renderer, const std::string& dir, const std::string& stem,
                                         float exposure, const Image* denoised) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("cannot create " + dir + ": " + ec.message());
    const std::string base = (std::filesystem::path(dir) / stem).string();
    std::vector<std::string> written;
#ifdef CLPATH_WITH_OIIO
    write_image(base + ".png", renderer.resolve(exposure));
    written.push_back(base + ".png");
    const std::string linear = base + ".exr";
#else
    const std::string linear = base + ".pfm";
#endif
    write_image(linear, renderer.resolve(1.0f));
    written.push_back(linear);
    if (denoised) {
        RenderedImage d;
        d.linear = *denoised;
        DisplaySettings display;
        display.exposure_stops = std::log2(exposure);
        d.srgb8 = display_srgb8(*denoised, display);  // the same clamp and sRGB curve as the film kernel's
        const auto twin = [&](const std::string& path) {
            const std::filesystem::path p(path);
            return (p.parent_path() / (p.stem().string() + ".denoised" + p.extension().string())).string();
        };
        for (std::size_t i = 0, n = written.size(); i < n; ++i) {
            write_image(twin(written[i]), d);
            written.push_back(twin(written[i]));
        }
    }
    return written;
}

void save_window_capture(const std::string& path, glm::ivec2 fb) {
    RenderedImage img;
    img.linear.width = fb.x;
    img.linear.height = fb.y;
    std::vector<std::uint8_t> rows(std::size_t(fb.x) * fb.y * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    // GL's row 0 is the bottom; images here start at the top.
    img.srgb8.resize(rows.size());
    const std::size_t stride = std::size_t(fb.x) * 4;
    for (int y = 0; y < fb.y; ++y)
        std::memcpy(img.srgb8.data() + std::size_t(y) * stride, rows.data() + std::size_t(fb.y - 1 - y) * stride, stride);
    for (std::size_t i = 3; i < img.srgb8.size(); i += 4) img.srgb8[i] = 255;  // the window is opaque
    img.linear.rgb.assign(std::size_t(fb.x) * fb.y * 3, 0.0f);  // unused by PNG; kept consistent in size
    write_image(path, img);
}

}  // namespace clpath::viewer
