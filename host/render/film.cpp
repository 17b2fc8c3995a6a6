#include "render/film.hpp"

#include "util/error.hpp"

namespace clpath {
namespace {

std::string size_text(int w, int h) { return std::to_string(w) + " x " + std::to_string(h); }

}  // namespace

std::vector<std::pair<std::string, std::size_t>> Film::memory_needs(int width, int height) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    return {{"accumulation film", pixels * sizeof(AccumPixel)}, {"linear image", pixels * 16}, {"sRGB image", pixels * 4}};
}

Film::Film(Context& ctx, int width, int height) : ctx_(ctx), width_(width), height_(height) {
    if (width < 1 || height < 1) throw Error("a film of " + size_text(width, height) + " pixels has no pixels");
    ctx.check_fits(memory_needs(width, height));
    const std::size_t pixels = pixel_count();
    accum_ = ctx.buffer(pixels * sizeof(AccumPixel), CL_MEM_READ_WRITE, "accumulation film");
    linear_ = ctx.buffer(pixels * 16, CL_MEM_WRITE_ONLY, "linear image");
    srgb_ = ctx.buffer(pixels * 4, CL_MEM_WRITE_ONLY, "sRGB image");
    clear();
}

void Film::clear() {
    ctx_.zero(accum_);
    samples_per_pixel_ = 0;
}

void Film::start_chunk_at(std::uint64_t first_sample) {
    if (first_sample > kMaxSamplesPerPixel)
        throw Error("a chunk starting at sample " + std::to_string(first_sample) + ": at most " +
                    std::to_string(kMaxSamplesPerPixel) + " samples per pixel");
    samples_per_pixel_ = first_sample;
}

void Film::count_samples(std::uint32_t n) {
    if (samples_per_pixel_ + n > kMaxSamplesPerPixel)
        throw Error("at most " + std::to_string(kMaxSamplesPerPixel) + " samples per pixel can be accumulated");
    samples_per_pixel_ += n;
}

FilmState Film::read_state() const {
    FilmState s;
    s.width = width_;
    s.height = height_;
    s.samples_per_pixel = samples_per_pixel_;
    s.pixels.resize(pixel_count());
    ctx_.read(accum_, s.pixels);
    return s;
}

void Film::write_state(const FilmState& s) {
    if (s.width != width_ || s.height != height_)
        throw Error("a film state of " + size_text(s.width, s.height) + " pixels cannot be loaded into a film of " +
                    size_text(width_, height_));
    if (s.pixels.size() != pixel_count())
        throw Error("a film state of " + size_text(s.width, s.height) + " pixels holds " +
                    std::to_string(s.pixels.size()) + " pixel records");
    if (s.samples_per_pixel > kMaxSamplesPerPixel)
        throw Error("a film state of " + std::to_string(s.samples_per_pixel) + " samples per pixel: at most " +
                    std::to_string(kMaxSamplesPerPixel) + " can be accumulated");
    ctx_.write(accum_, s.pixels);
    samples_per_pixel_ = s.samples_per_pixel;
}

void Film::resolve_on_device(Kernel& resolve, float exposure) {
    const std::uint32_t pixels = pixel_count();
    const float inv = samples_per_pixel_ ? float(1.0 / double(samples_per_pixel_)) : 0.0f;
    resolve.arg(0, accum_).arg(1, pixels).arg(2, inv).arg(3, exposure).arg(4, linear_).arg(5, srgb_);
    ctx_.launch(resolve, pixels, 0);
}

RenderedImage Film::read_image() const {
    const std::size_t pixels = pixel_count();
    std::vector<float> rgba(pixels * 4);
    RenderedImage out;
    out.srgb8.resize(pixels * 4);
    ctx_.read(linear_, rgba.data(), rgba.size() * sizeof(float));
    ctx_.read(srgb_, out.srgb8.data(), out.srgb8.size());
    out.linear.width = width_;
    out.linear.height = height_;
    out.linear.rgb.resize(pixels * 3);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) out.linear.rgb[i * 3 + c] = rgba[i * 4 + c];
    return out;
}

}  // namespace clpath
