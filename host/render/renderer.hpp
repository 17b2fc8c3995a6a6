#pragma once
// The progressive renderer, for callers that render one scene on one device:
// a composition of the parts, as pbrt separates aggregate, film and integrator.
//   PreparedScene      (prepared_scene.hpp)     validation, BVH, light table, environment; host, built once
//   DeviceScene        (device_scene.hpp)       that scene's arrays on one device
//   Film               (film.hpp)               the running sums, their sample count, the resolve
//   IntegratorProgram  (integrator_program.hpp) the compiled kernels and the launches
#include <cstdint>
#include <memory>
#include <vector>

#include "bvh/bvh.hpp"
#include "cl/context.hpp"
#include "image/image.hpp"
#include "render/device_exact_film.hpp"
#include "render/device_scene.hpp"
#include "render/film.hpp"
#include "render/integrator_program.hpp"
#include "render/kernel_features.hpp"
#include "render/prepared_scene.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {

struct RenderStats : LaunchStats {
    std::uint64_t samples_per_pixel = 0;
};

class Renderer {
public:
    // Prepares the scene (validation, BVH), checks that everything fits on
    // the device, uploads and compiles. Throws clpath::Error with the reason
    // when any step fails.
    Renderer(Context& ctx, const Scene& scene, const RenderSettings& settings);
    // The same from a scene already prepared (with the same settings.accel),
    // which may be uploaded to other devices too; it is not kept.
    Renderer(Context& ctx, const PreparedScene& scene, const RenderSettings& settings);
    // The same with a variant of the kernels (bench render-ab).
    Renderer(Context& ctx, const PreparedScene& scene, const RenderSettings& settings, KernelVariant variant);

    // Adds n samples per pixel (in as many launches as the time target asks).
    void add_samples(std::uint32_t n);
    // Starts the mean again (the viewer's camera moved), keeping the scene.
    void reset();
    // A camera of the same resolution; restarts the mean.
    void set_camera(const Camera& camera);
    // A camera of any resolution: another size gets a new film, keeping the
    // device scene and the kernels (a viewer's resize). The old film stays
    // until the new one is made, so a failure (too large for the device)
    // leaves the renderer as it was. Restarts the mean.
    void resize(const Camera& camera);
    // New settings restart the mean; the kernels are rebuilt (or loaded from
    // the cache) when the features they need change, e.g. another integrator.
    void set_settings(const RenderSettings& settings);
    const RenderSettings& settings() const { return program_->settings(); }

    // Chunked renders (render/device_farm.hpp): the film, which must be empty
    // (new, or emptied by add_chunk_to), takes samples from first_sample on;
    // after add_samples, add_chunk_to adds them to an exact film on the same
    // device and empties the film. Nothing is read back.
    void start_chunk(std::uint64_t first_sample) { film_->start_chunk_at(first_sample); }
    void add_chunk_to(DeviceExactFilm& exact, std::uint32_t samples) {
        exact.add_chunk(*film_, program_->add_exact_kernel(), samples,
                        exact.has_half() ? &program_->add_exact_half_kernel() : nullptr);
    }
    // Adaptive sampling (render/adaptive.hpp): only the pixels whose byte is
    // non-zero take samples from now on, and the film gathers the half film
    // (add chunks to a DeviceExactFilm made with one). nullptr: every pixel.
    void set_active_pixels(const std::vector<std::uint8_t>* mask) {
        program_->set_active_pixels(mask, film_->pixel_count());
    }

    // The mean, scaled by exposure, as linear float and 8-bit sRGB, read back.
    RenderedImage resolve(float exposure = 1.0f);
    // The same, left on the device in srgb_buffer() (RGBA8, row 0 at the top):
    // for a viewer that shares it with OpenGL.
    void resolve_on_device(float exposure = 1.0f);
    const Buffer& srgb_buffer() const { return film_->srgb_buffer(); }
    // The flattened BVH, kept on the host for the viewer's box overlay (empty with Accel::Flat).
    const BvhNodes& bvh_nodes() const { return bvh_nodes_; }

    // The film's sample count and the launches' totals since the last reset.
    RenderStats stats() const;
    const BvhStats& bvh_stats() const { return scene_->summary().bvh_stats; }
    std::size_t triangle_count() const { return scene_->summary().triangle_count; }
    double compile_seconds() const { return program_->compile_seconds(); }
    bool compiled_from_cache() const { return program_->compiled_from_cache(); }
    const Camera& camera() const { return camera_; }

    // The parts, for callers that need more than this composition (film state
    // for checkpoints and merges).
    const DeviceScene& device_scene() const { return *scene_; }
    Film& film() { return *film_; }
    const Film& film() const { return *film_; }

private:
    Context& ctx_;
    Camera camera_;
    BvhNodes bvh_nodes_;
    std::unique_ptr<DeviceScene> scene_;
    std::unique_ptr<Film> film_;
    std::unique_ptr<IntegratorProgram> program_;
};

}  // namespace clpath
