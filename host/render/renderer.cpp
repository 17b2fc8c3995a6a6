#include "render/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cl/embedded_sources.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

constexpr std::uint32_t kTile = 8;        // kernels/integrator.cl CLP_TILE
constexpr std::size_t kWorkGroup = 64;

void validate_scene(const Scene& s) {
    if (s.triangle_count() == 0) throw Error("scene '" + s.name + "' has no triangles");
    if (s.vertices.size() != s.triangle_count() * 3)
        throw Error("internal: scene '" + s.name + "' has " + std::to_string(s.vertices.size()) +
                    " vertices for " + std::to_string(s.triangle_count()) + " triangles");
    for (auto m : s.triangle_material)
        if (m >= s.materials.size()) throw Error("internal: triangle material index out of range");
}

}  // namespace

std::string renderer_build_options(const Scene&) {
    // Scene-specific feature switches join these when more material and light kinds exist.
    return "-cl-std=CL1.2";
}

Renderer::Renderer(Context& ctx, const Scene& scene, const RenderSettings& settings)
    : ctx_(ctx), settings_(settings), camera_(scene.camera) {
    validate_scene(scene);
    triangle_count_ = scene.triangle_count();
    const CameraData cam = camera_data(camera_);  // validates the camera before any work

    Bvh bvh = build_bvh(scene.vertices, settings.bvh);
    bvh_stats_ = bvh.stats;
    bvh_nodes_ = bvh.nodes;

    const std::size_t pixels = std::size_t(camera_.width) * camera_.height;
    ctx.check_fits({{"BVH nodes", bvh.nodes.size() * sizeof(BvhNode)},
                    {"triangles", bvh.triangles.size() * sizeof(TriVerts)},
                    {"triangle materials", scene.triangle_material.size() * sizeof(std::uint32_t)},
                    {"materials", scene.materials.size() * sizeof(Material)},
                    {"accumulation film", pixels * sizeof(AccumPixel)},
                    {"linear image", pixels * 16},
                    {"sRGB image", pixels * 4}});
    nodes_ = ctx.buffer(bvh.nodes.size() * sizeof(BvhNode), CL_MEM_READ_ONLY, "BVH nodes", bvh.nodes.data());
    tris_ = ctx.buffer(bvh.triangles.size() * sizeof(TriVerts), CL_MEM_READ_ONLY, "triangles",
                       bvh.triangles.data());
    tri_material_ = ctx.buffer(scene.triangle_material.size() * sizeof(std::uint32_t), CL_MEM_READ_ONLY,
                               "triangle materials", scene.triangle_material.data());
    materials_ = ctx.buffer(scene.materials.size() * sizeof(Material), CL_MEM_READ_ONLY, "materials",
                            scene.materials.data());
    params_ = ctx.buffer(sizeof(FrameParams), CL_MEM_READ_ONLY, "frame parameters");
    counters_ = ctx.buffer(sizeof(Counters), CL_MEM_READ_WRITE, "counters");
    accum_ = ctx.buffer(pixels * sizeof(AccumPixel), CL_MEM_READ_WRITE, "accumulation film");
    linear_ = ctx.buffer(pixels * 16, CL_MEM_WRITE_ONLY, "linear image");
    srgb_ = ctx.buffer(pixels * 4, CL_MEM_WRITE_ONLY, "sRGB image");
    (void)cam;

    BuildResult built = build_program(ctx, program_source(renderer_kernel_files()), renderer_build_options(scene));
    program_ = std::move(built.program);
    compile_seconds_ = built.seconds;
    from_cache_ = built.from_cache;
    render_ = ctx.kernel(program_.get(), "render_paths");
    clear_ = ctx.kernel(program_.get(), "film_clear");
    resolve_ = ctx.kernel(program_.get(), "film_resolve");
    reset();
}

std::size_t Renderer::device_bytes() const { return ctx_.allocated_bytes(); }

std::uint32_t Renderer::tiled_pixel_count() const {
    const std::uint32_t tx = (std::uint32_t(camera_.width) + kTile - 1) / kTile;
    const std::uint32_t ty = (std::uint32_t(camera_.height) + kTile - 1) / kTile;
    return tx * ty * kTile * kTile;
}

void Renderer::reset() {
    const std::uint32_t pixels = std::uint32_t(camera_.width) * std::uint32_t(camera_.height);
    clear_.arg(0, accum_).arg(1, pixels);
    ctx_.launch(clear_, pixels, 0);
    ctx_.finish();
    stats_ = RenderStats{};
}

void Renderer::set_camera(const Camera& camera) {
    if (camera.width != camera_.width || camera.height != camera_.height)
        throw Error("internal: set_camera cannot change the resolution");
    camera_data(camera);  // validates
    camera_ = camera;
    reset();
}

void Renderer::set_settings(const RenderSettings& settings) { settings_ = settings; }

void Renderer::launch_band(std::uint32_t first_pixel, std::uint32_t pixel_count, std::uint32_t samples) {
    FrameParams fp{};
    fp.camera = camera_data(camera_);
    fp.seed = settings_.seed;
    fp.first_sample = std::uint32_t(stats_.samples_per_pixel);
    fp.samples = samples;
    fp.max_depth = settings_.max_depth;
    fp.rr_rule = settings_.rr_rule;
    fp.rr_min_depth = settings_.rr_min_depth;
    fp.pixel_offset = first_pixel;
    fp.pixel_count = pixel_count;
    const Counters zero{};
    ctx_.write(params_, &fp, sizeof fp);
    ctx_.write(counters_, &zero, sizeof zero);
    render_.arg(0, nodes_).arg(1, tris_).arg(2, tri_material_).arg(3, materials_).arg(4, params_).arg(5, accum_).arg(
        6, counters_);
    const auto t0 = std::chrono::steady_clock::now();
    ctx_.launch(render_, pixel_count, kWorkGroup);
    Counters c{};
    ctx_.read(counters_, &c, sizeof c);  // blocking: the launch has finished
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats_.render_seconds += dt;
    stats_.rays += c.rays;
    stats_.nonfinite += c.nonfinite;
    ++stats_.launches;
    const double work = double(pixel_count) * samples;
    // Smoothed, so one slow launch does not swing the next one's size.
    const double s = dt / work;
    seconds_per_pixel_sample_ = seconds_per_pixel_sample_ > 0 ? 0.5 * (seconds_per_pixel_sample_ + s) : s;
}

void Renderer::add_samples(std::uint32_t n) {
    if (stats_.samples_per_pixel + n > kMaxSamplesPerPixel)
        throw Error("at most " + std::to_string(kMaxSamplesPerPixel) + " samples per pixel can be accumulated");
    const std::uint32_t all = tiled_pixel_count();
    // Each launch's ray counter is 32-bit: keep pixels * samples * segments well below 2^32.
    const double max_work = 0xffffffffu / double(settings_.max_depth + 2);
    while (n > 0) {
        const double target = settings_.target_launch_seconds;
        std::uint32_t samples = 1, band = all;
        if (seconds_per_pixel_sample_ <= 0) {
            band = std::min<std::uint32_t>(all, 16384);  // first launch: small, to measure
        } else {
            const double per_frame = seconds_per_pixel_sample_ * all;
            if (per_frame > target) {
                band = std::uint32_t(std::clamp(target / seconds_per_pixel_sample_, double(kWorkGroup), double(all)));
                band = std::max<std::uint32_t>(kWorkGroup, band / kWorkGroup * kWorkGroup);
            } else {
                samples = std::uint32_t(std::clamp(target / per_frame, 1.0, double(n)));
            }
        }
        samples = std::uint32_t(std::min<double>(samples, std::max(1.0, max_work / all)));
        for (std::uint32_t first = 0; first < all; first += band)
            launch_band(first, std::min(band, all - first), samples);
        stats_.samples_per_pixel += samples;
        n -= samples;
    }
}

void Renderer::resolve_on_device(float exposure) {
    const std::uint32_t pixels = std::uint32_t(camera_.width) * std::uint32_t(camera_.height);
    const float inv = stats_.samples_per_pixel ? float(1.0 / double(stats_.samples_per_pixel)) : 0.0f;
    resolve_.arg(0, accum_).arg(1, pixels).arg(2, inv).arg(3, exposure).arg(4, linear_).arg(5, srgb_);
    ctx_.launch(resolve_, pixels, 0);
}

RenderedImage Renderer::resolve(float exposure) {
    const std::uint32_t pixels = std::uint32_t(camera_.width) * std::uint32_t(camera_.height);
    resolve_on_device(exposure);
    std::vector<float> rgba(std::size_t(pixels) * 4);
    RenderedImage out;
    out.srgb8.resize(std::size_t(pixels) * 4);
    ctx_.read(linear_, rgba.data(), rgba.size() * sizeof(float));
    ctx_.read(srgb_, out.srgb8.data(), out.srgb8.size());
    out.linear.width = camera_.width;
    out.linear.height = camera_.height;
    out.linear.rgb.resize(std::size_t(pixels) * 3);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) out.linear.rgb[i * 3 + c] = rgba[i * 4 + c];
    return out;
}

}  // namespace clpath
