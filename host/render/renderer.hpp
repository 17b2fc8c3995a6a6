#pragma once
// The progressive renderer: owns the scene's device buffers and the compiled
// kernels, adds samples in short launches, and resolves the running mean.
#include <cstdint>
#include <string>

#include "bvh/bvh.hpp"
#include "cl/context.hpp"
#include "cl/program.hpp"
#include "image/image.hpp"
#include "render/kernel_features.hpp"
#include "render/settings.hpp"
#include "scene/scene.hpp"

namespace clpath {


struct RenderStats {
    std::uint64_t samples_per_pixel = 0;
    std::uint64_t rays = 0;       // every ray traced
    std::uint64_t nonfinite = 0;  // samples dropped as NaN/inf
    std::uint64_t launches = 0;
    double render_seconds = 0;    // wall time spent in launches, to their completion
};

// Largest samples-per-pixel count one render may reach: the kernels index
// samples with 32-bit integers.
constexpr std::uint64_t kMaxSamplesPerPixel = 0xffffffffull;

// Most rays one sample can trace, for any integrator: a path traces its
// camera ray and one ray per bounce (max_depth + 1) and one shadow ray per
// bounce (max_depth); ambient occlusion 2. Launches are sized so that the
// kernels' 32-bit ray counter cannot overflow (host totals are 64-bit).
constexpr std::uint64_t max_rays_per_sample(const RenderSettings& s) { return 2ull * s.max_depth + 2; }

class Renderer {
public:
    // Builds the BVH, checks that everything fits on the device, uploads and
    // compiles. Throws clpath::Error with the reason when any step fails.
    Renderer(Context& ctx, const Scene& scene, const RenderSettings& settings);

    // Adds n samples per pixel (in as many launches as the time target asks).
    void add_samples(std::uint32_t n);
    // Starts the mean again (the viewer's camera moved), keeping the scene.
    void reset();
    void set_camera(const Camera& camera);
    // New settings restart the mean; the kernels are rebuilt (or loaded from
    // the cache) when the features they need change, e.g. another integrator.
    void set_settings(const RenderSettings& settings);
    const RenderSettings& settings() const { return settings_; }
    const KernelFeatures& features() const { return features_; }

    // The mean, scaled by exposure, as linear float and 8-bit sRGB, read back.
    RenderedImage resolve(float exposure = 1.0f);
    // The same, left on the device in srgb_buffer() (RGBA8, row 0 at the top)
    // and linear_buffer() (RGBA float): for a viewer that shares them with OpenGL.
    void resolve_on_device(float exposure = 1.0f);
    const Buffer& srgb_buffer() const { return srgb_; }
    const Buffer& linear_buffer() const { return linear_; }
    // The flattened BVH, kept on the host for the viewer's box overlay (empty with Accel::Flat).
    const std::vector<BvhNode>& bvh_nodes() const { return bvh_nodes_; }

    const RenderStats& stats() const { return stats_; }
    const BvhStats& bvh_stats() const { return bvh_stats_; }
    std::size_t triangle_count() const { return triangle_count_; }
    std::size_t light_count() const { return light_count_; }
    double compile_seconds() const { return compile_seconds_; }
    bool compiled_from_cache() const { return from_cache_; }
    const Camera& camera() const { return camera_; }
    std::size_t device_bytes() const;

private:
    void launch_band(std::uint32_t first_pixel, std::uint32_t pixel_count, std::uint32_t samples);
    void compile();
    std::uint32_t tiled_pixel_count() const;

    Context& ctx_;
    RenderSettings settings_;
    Camera camera_;
    BvhStats bvh_stats_;
    std::vector<BvhNode> bvh_nodes_;
    std::size_t triangle_count_ = 0, light_count_ = 0;
    SceneFeatures scene_features_;
    KernelFeatures features_;
    std::uint32_t env_light_ = CLP_NO_LIGHT;
    int env_width_ = 0, env_height_ = 0;
    glm::vec3 env_color_{0};
    float env_scale_ = 1, env_rotation_ = 0;
    float scene_diagonal_ = 1;
    Buffer nodes_, tris_, tri_material_, materials_, normals_, lights_, alias_, env_pixels_, env_cdf_;
    Buffer params_, accum_, counters_, linear_, srgb_;
    Buffer attrs_, tex_desc_, texels_;  // surface attributes and textures (render/surface_buffers.hpp)
    std::uint32_t attr_stride_ = 0, surface_flags_ = 0;
    Program program_;
    Kernel render_, clear_, resolve_;
    RenderStats stats_;
    double compile_seconds_ = 0;
    bool from_cache_ = false;
    double seconds_per_pixel_sample_ = 0;  // measured; sizes the launches
};

}  // namespace clpath
