#include "render/renderer.hpp"

#include <utility>

#include "util/error.hpp"

namespace clpath {
namespace {

// The settings and the camera are checked before any work on the scene.
const Scene& checked(const Scene& scene, const RenderSettings& settings) {
    validate_settings(settings);
    camera_data(scene.camera);
    return scene;
}

}  // namespace

// The prepared scene (a temporary) lives until the delegated constructor returns.
Renderer::Renderer(Context& ctx, const Scene& scene, const RenderSettings& settings)
    : Renderer(ctx, *prepare_scene(checked(scene, settings), settings), settings) {}

Renderer::Renderer(Context& ctx, const PreparedScene& scene, const RenderSettings& settings)
    : Renderer(ctx, scene, settings, KernelVariant{}) {}

Renderer::Renderer(Context& ctx, const PreparedScene& scene, const RenderSettings& settings, KernelVariant variant)
    : ctx_(ctx), camera_(scene.camera) {
    validate_settings(settings);
    camera_data(camera_);
    {
        // Everything at once, so that a scene too large is refused before any
        // upload; the nodes widened once, for the sizing and the upload.
        const std::vector<unsigned char> node_bytes =
            scene_node_bytes(scene, DeviceScene::device_node_layout(ctx.device(), scene));
        auto needs = DeviceScene::memory_needs(scene, node_bytes.size());
        for (auto& n : Film::memory_needs(camera_.width, camera_.height)) needs.push_back(std::move(n));
        ctx.check_fits(needs);
        scene_ = std::make_unique<DeviceScene>(ctx, scene, node_bytes);
    }
    film_ = std::make_unique<Film>(ctx, camera_.width, camera_.height);
    program_ = std::make_unique<IntegratorProgram>(ctx, scene.summary, settings, std::move(variant));
    if (scene.summary.accel == Accel::Bvh) bvh_nodes_ = scene.accel.nodes;  // the flat list is no tree to draw
}

RenderStats Renderer::stats() const {
    RenderStats s;
    static_cast<LaunchStats&>(s) = program_->stats();
    s.samples_per_pixel = film_->samples_per_pixel();
    return s;
}

void Renderer::add_samples(std::uint32_t n) { program_->add_samples(*scene_, *film_, camera_, n); }

void Renderer::reset() {
    film_->clear();
    program_->reset_stats();
}

void Renderer::set_camera(const Camera& camera) {
    if (camera.width != camera_.width || camera.height != camera_.height)
        throw Error("internal: set_camera cannot change the resolution");
    camera_data(camera);  // validates
    camera_ = camera;
    reset();
}

void Renderer::resize(const Camera& camera) {
    if (camera.width == camera_.width && camera.height == camera_.height) return set_camera(camera);
    camera_data(camera);
    auto fresh = std::make_unique<Film>(ctx_, camera.width, camera.height);
    film_ = std::move(fresh);
    camera_ = camera;
    program_->reset_stats();
}

void Renderer::set_settings(const RenderSettings& settings) {
    program_->set_settings(settings);
    reset();
}

void Renderer::resolve_on_device(float exposure) { film_->resolve_on_device(program_->resolve_kernel(), exposure); }

RenderedImage Renderer::resolve(float exposure) {
    resolve_on_device(exposure);
    return film_->read_image();
}

}  // namespace clpath
