#include "render/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cl/embedded_sources.hpp"
#include "render/environment_map.hpp"
#include "render/light_table.hpp"
#include "render/surface_buffers.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

constexpr std::uint32_t kTile = 8;        // kernels/integrator.cl CLP_TILE
constexpr std::size_t kWorkGroup = 64;

void validate_settings(const RenderSettings& s) {
    if (s.integrator >= CLP_INTEGRATOR_COUNT) throw Error("internal: unknown integrator");
    if (s.rr_rule == CLP_RR_DEPTH && s.max_depth < 1)
        throw Error("the depth Russian roulette rule needs a maximum depth of at least 1");
}

void validate_scene(const Scene& s) {
    if (s.triangle_count() == 0) throw Error("scene '" + s.name + "' has no triangles");
    if (s.vertices.size() != s.triangle_count() * 3)
        throw Error("internal: scene '" + s.name + "' has " + std::to_string(s.vertices.size()) +
                    " vertices for " + std::to_string(s.triangle_count()) + " triangles");
    for (auto m : s.triangle_material)
        if (m >= s.materials.size()) throw Error("internal: triangle material index out of range");
    if (!s.normals.empty() && s.normals.size() != s.vertices.size())
        throw Error("internal: scene '" + s.name + "' has normals for some vertices only");
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        const Material& m = s.materials[i];
        const std::string name = i < s.material_names.size() ? s.material_names[i] : std::to_string(i);
        if (m.kind >= CLP_MAT_KIND_COUNT) throw Error("material '" + name + "': unknown kind");
        if (m.kind == CLP_MAT_DIELECTRIC && !(m.ior > 0))
            throw Error("material '" + name + "': index of refraction must be positive");
        for (int t : m.texture)
            if (t != CLP_NO_TEXTURE && (t < 0 || std::size_t(t) >= s.textures.size()))
                throw Error("internal: material '" + name + "' names texture " + std::to_string(t));
    }
    if ((!s.uvs.empty() && s.uvs.size() != s.vertices.size()) || (!s.tangents.empty() && s.tangents.size() != s.vertices.size()) ||
        (!s.colors.empty() && s.colors.size() != s.vertices.size()))
        throw Error("internal: texture coordinates, tangents or colours for some vertices only");
}

}  // namespace

Renderer::Renderer(Context& ctx, const Scene& scene, const RenderSettings& settings)
    : ctx_(ctx), settings_(settings), camera_(scene.camera) {
    validate_scene(scene);
    validate_settings(settings);
    triangle_count_ = scene.triangle_count();
    camera_data(camera_);  // validates the camera before any work
    scene_features_ = scene_features(scene);
    features_ = kernel_features(scene_features_, settings_);

    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : scene.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    scene_diagonal_ = glm::length(hi - lo);
    if (!(scene_diagonal_ > 0) || !std::isfinite(scene_diagonal_)) scene_diagonal_ = 1;

    // The environment and the light table are built for next-event estimation
    // whatever the current integrator, so switching integrators rebuilds nothing.
    const EnvironmentMap env = load_environment_map(scene.environment);
    env_width_ = env.width;
    env_height_ = env.height;
    env_color_ = scene.environment.color;
    env_scale_ = scene.environment.scale;
    env_rotation_ = glm::radians(scene.environment.rotation_degrees);
    RenderSettings path_settings = settings_;
    path_settings.integrator = CLP_INTEGRATOR_PATH;
    path_settings.all_features = false;
    const LightTable lights =
        build_light_table(scene, kernel_features(scene_features_, path_settings), env, 0.5f * scene_diagonal_);
    light_count_ = lights.lights.size();
    env_light_ = lights.environment;

    if (settings.accel == Accel::Flat && scene.triangle_object.size() != scene.triangle_count())
        throw Error("internal: scene '" + scene.name + "' has no object id for every triangle (needed by --accel flat)");
    Bvh bvh = build_accel(settings.accel, scene.vertices, scene.triangle_object, settings.bvh);
    bvh_stats_ = bvh.stats;
    for (auto& t : bvh.triangles) t.light = lights.light_of_triangle[t.prim];
    if (settings.accel == Accel::Bvh) bvh_nodes_ = bvh.nodes;  // the flat list is no tree to draw

    // Kernels take no empty buffers: a missing part gets one zero record.
    const std::size_t pixels = std::size_t(camera_.width) * camera_.height;
    const std::size_t normal_bytes = std::max<std::size_t>(16, scene.normals.size() * 12);
    const std::size_t light_bytes = std::max<std::size_t>(1, light_count_) * sizeof(Light);
    const std::size_t alias_bytes = std::max<std::size_t>(1, light_count_) * sizeof(AliasEntry);
    ctx.check_fits({{"BVH nodes", bvh.nodes.size() * sizeof(BvhNode)},
                    {"triangles", bvh.triangles.size() * sizeof(TriVerts)},
                    {"triangle materials", scene.triangle_material.size() * sizeof(std::uint32_t)},
                    {"materials", scene.materials.size() * sizeof(Material)},
                    {"shading normals", normal_bytes},
                    {"lights", light_bytes + alias_bytes},
                    {"environment image", env.pixels.size() * sizeof(float)},
                    {"environment distribution", env.cdf.size() * sizeof(float)},
                    {"surface attributes", surface_attribute_bytes(scene)},
                    {"textures", texture_bytes(scene)},
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
    std::vector<float> zeros(16, 0.0f);
    normals_ = ctx.buffer(normal_bytes, CL_MEM_READ_ONLY, "shading normals",
                          scene.normals.empty() ? static_cast<const void*>(zeros.data()) : scene.normals.data());
    const Light no_light{};
    const AliasEntry no_alias{};
    lights_ = ctx.buffer(light_bytes, CL_MEM_READ_ONLY, "lights",
                         light_count_ ? static_cast<const void*>(lights.lights.data()) : &no_light);
    alias_ = ctx.buffer(alias_bytes, CL_MEM_READ_ONLY, "light alias table",
                        light_count_ ? static_cast<const void*>(lights.alias.data()) : &no_alias);
    env_pixels_ = ctx.buffer(env.pixels.size() * sizeof(float), CL_MEM_READ_ONLY, "environment image",
                             env.pixels.data());
    env_cdf_ = ctx.buffer(env.cdf.size() * sizeof(float), CL_MEM_READ_ONLY, "environment distribution",
                          env.cdf.data());
    {
        // Texture coordinates, tangents, colours and textures: a 16-byte stand-in when the scene has none.
        const SurfaceBuffers surf = pack_surface_buffers(scene);
        attr_stride_ = surf.attr_stride;
        surface_flags_ = surf.scene_flags;
        auto upload = [&](std::size_t bytes, const void* data, const char* what) {
            static const std::uint32_t none[4] = {0, 0, 0, 0};
            return bytes ? ctx.buffer(bytes, CL_MEM_READ_ONLY, what, data) : ctx.buffer(16, CL_MEM_READ_ONLY, what, none);
        };
        attrs_ = upload(surf.attrs.size() * sizeof(float), surf.attrs.data(), "surface attributes");
        tex_desc_ = upload(surf.textures.size() * sizeof(TextureDesc), surf.textures.data(), "texture descriptors");
        texels_ = upload(surf.texels.size() * sizeof(std::uint32_t), surf.texels.data(), "texels");
    }
    params_ = ctx.buffer(sizeof(FrameParams), CL_MEM_READ_ONLY, "frame parameters");
    counters_ = ctx.buffer(sizeof(Counters), CL_MEM_READ_WRITE, "counters");
    accum_ = ctx.buffer(pixels * sizeof(AccumPixel), CL_MEM_READ_WRITE, "accumulation film");
    linear_ = ctx.buffer(pixels * 16, CL_MEM_WRITE_ONLY, "linear image");
    srgb_ = ctx.buffer(pixels * 4, CL_MEM_WRITE_ONLY, "sRGB image");

    compile();
    reset();
}

void Renderer::compile() {
    BuildResult built = build_program(ctx_, program_source(renderer_kernel_files()), build_options(features_));
    render_ = Kernel();
    clear_ = Kernel();
    resolve_ = Kernel();
    program_ = std::move(built.program);
    compile_seconds_ = built.seconds;
    from_cache_ = built.from_cache;
    render_ = ctx_.kernel(program_.get(), "render_paths");
    clear_ = ctx_.kernel(program_.get(), "film_clear");
    resolve_ = ctx_.kernel(program_.get(), "film_resolve");
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

void Renderer::set_settings(const RenderSettings& settings) {
    validate_settings(settings);
    if (settings.accel != settings_.accel)
        throw Error(std::string("the acceleration structure cannot change in a running renderer (it was built as ") +
                    accel_name(settings_.accel) + "); make a new renderer for " + accel_name(settings.accel));
    settings_ = settings;
    const KernelFeatures f = kernel_features(scene_features_, settings_);
    if (!(f == features_)) {
        features_ = f;
        compile();
    }
    seconds_per_pixel_sample_ = 0;  // another integrator runs at another speed
    reset();
}

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
    fp.light_count = settings_.integrator == CLP_INTEGRATOR_PATH ? std::uint32_t(light_count_) : 0u;
    fp.env_light = env_light_;
    fp.ao_distance = settings_.ao_distance > 0 ? settings_.ao_distance : 0.1f * scene_diagonal_;
    fp.depth_scale = scene_diagonal_;
    fp.env_color[0] = env_color_.x;
    fp.env_color[1] = env_color_.y;
    fp.env_color[2] = env_color_.z;
    fp.env_width = std::uint32_t(env_width_);
    fp.env_height = std::uint32_t(env_height_);
    fp.env_scale = env_scale_;
    fp.env_rot_cos = std::cos(env_rotation_);
    fp.env_rot_sin = std::sin(env_rotation_);
    fp.scene_flags = (scene_features_.normals ? CLP_SCENE_NORMALS : 0u) | surface_flags_;
    fp.attr_stride = attr_stride_;
    const Counters zero{};
    ctx_.write(params_, &fp, sizeof fp);
    ctx_.write(counters_, &zero, sizeof zero);
    render_.arg(0, nodes_).arg(1, tris_).arg(2, tri_material_).arg(3, materials_).arg(4, normals_).arg(5, lights_);
    render_.arg(6, alias_).arg(7, env_pixels_).arg(8, env_cdf_).arg(9, params_).arg(10, accum_).arg(11, counters_);
    render_.arg(12, attrs_).arg(13, tex_desc_).arg(14, texels_);
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
    // Each launch's ray counter is 32-bit: keep pixels * samples * rays per
    // sample below 2^32, by fewer samples per launch and, where one sample of
    // every pixel is already too much (a 16384^2 film at depth 1024), by bands.
    const double max_work = double(0xffffffffu) / double(max_rays_per_sample(settings_));
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
        if (double(band) * samples > max_work)
            band = std::max<std::uint32_t>(kWorkGroup, std::uint32_t(max_work / samples) / kWorkGroup * kWorkGroup);
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
