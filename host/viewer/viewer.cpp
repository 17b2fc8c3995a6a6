// The viewer's loop: input (window and script) -> camera and settings ->
// samples for this frame's budget -> image into the window -> overlay and HUD.
#include "viewer/viewer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "cl/device.hpp"
#include "render/renderer.hpp"
#include "render/settings.hpp"
#include "scene/load/scene_loader.hpp"
#include "util/error.hpp"
#include "viewer/bvh_overlay.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/camera_snippet.hpp"
#include "viewer/display.hpp"
#include "viewer/focus_pick.hpp"
#include "viewer/frame_pacer.hpp"
#include "viewer/hud.hpp"
#include "viewer/keymap.hpp"
#include "viewer/screenshot.hpp"
#include "viewer/sigint.hpp"
#include "viewer/state_log.hpp"
#include "viewer/view_denoiser.hpp"
#include "viewer/view_script.hpp"
#include "viewer/window.hpp"

namespace clpath {
namespace {

using namespace viewer;
using Clock = std::chrono::steady_clock;
using json = nlohmann::json;

// A resize is followed once the size has held this long: a new film on every
// step of a drag would allocate and clear dozens of them.
constexpr double kResizeSettleSeconds = 0.2;
// A slow frame must not turn into a jump: movement uses at most this much time.
constexpr float kMaxMoveSeconds = 0.25f;
constexpr int kDefaultBvhDepth = 3;

float scene_diagonal(const Scene& s) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& v : s.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const float d = glm::length(hi - lo);
    return std::isfinite(d) && d > 0 ? d : 1.0f;
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

json vec_json(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

Scene load_for_viewer(const ViewerOptions& o, RenderSettings& settings) {
    Scene scene = load_scene(o.scene);
    for (const auto& w : scene.warnings) std::fprintf(stderr, "clpath: warning: %s\n", w.c_str());
    for (const auto& n : scene.notes) std::fprintf(stderr, "clpath: %s\n", n.c_str());
    // The scene file's render block gives the defaults; options override the settings.
    settings = settings_from_scene(scene.render);
    if (o.seed) settings.seed = *o.seed;
    if (o.max_depth) settings.max_depth = *o.max_depth;
    if (o.integrator) settings.integrator = parse_integrator(*o.integrator);
    // Launches no longer than a frame keep the window responsive.
    settings.target_launch_seconds = o.frame_ms / 1000.0;
    if (o.width) scene.camera.width = o.width;
    if (o.height) scene.camera.height = o.height;
    if (!scene.has_emitter())
        std::fprintf(stderr, "clpath: warning: scene '%s' has no emitter; the path image will be black\n",
                     scene.name.c_str());
    return scene;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
    return path.empty() ? std::vector<ScriptCommand>{} : load_view_script(path);
}

class Viewer {
public:
    explicit Viewer(const ViewerOptions& o)
        : o_(o),
          scene_(load_for_viewer(o, settings_)),
          script_(load_script(o.script)),
          device_(select_device(o.device)),  // before the window: no device, no window
          diagonal_(scene_diagonal(scene_)),
          window_(scene_.camera.width, scene_.camera.height, "clpath view - " + scene_.name),
          display_context_(make_display_context(device_)),
          fly_(scene_.camera, 0.25f * diagonal_),
          pacer_(o.frame_ms / 1000.0),
          log_(o.state_log),
          exposure_(o.exposure) {
        std::fprintf(stderr, "clpath: viewing '%s' (%zu triangles) with '%s' on %s\n", scene_.name.c_str(),
                     scene_.triangle_count(), integrator_name(settings_.integrator), device_.describe().c_str());
        std::fprintf(stderr, "clpath: display path: %s\n", display_context_.path.c_str());
        create_renderer(render_size(window_.framebuffer_size()));
        display_ = std::make_unique<Display>(*display_context_.context, display_context_.shared);
        overlay_ = std::make_unique<BvhOverlay>();
        bvh_levels_ = bvh_levels(renderer_->bvh_nodes());
        hud_ = std::make_unique<Hud>(window_.get());
        if (o.hide_hud) hud_->toggle();
        // The guides take at most half a frame's budget while they are made.
        denoiser_ = std::make_unique<ViewDenoiser>(o.frame_ms / 2000.0);
    }

    int run() {
        const auto start = Clock::now();
        auto frame_start = start;
        while (!quit_ && !window_.should_close() && !sigint_.raised()) {
            if (o_.frames > 0 && frame_ >= o_.frames) {
                if (!script_.finished())
                    throw Error("--frames " + std::to_string(o_.frames) + " reached before the script finished (at line " +
                                std::to_string(script_.current_line()) + ")");
                break;
            }
            const float dt = float(seconds_since(frame_start));
            frame_start = Clock::now();
            step(std::min(dt, kMaxMoveSeconds));
            ++frame_;
            frame_ms_ = smooth(frame_ms_, 1000.0 * seconds_since(frame_start));
        }
        const double wall = seconds_since(start);
        std::fprintf(stderr, "clpath: viewer: %ld frames in %.1f s (%.1f frames/s), %llu spp at the end%s\n", frame_,
                     wall, wall > 0 ? frame_ / wall : 0.0, (unsigned long long)renderer_->stats().samples_per_pixel,
                     sigint_.raised() ? " (interrupted)" : "");
        return 0;
    }

private:
    static double smooth(double old, double now) { return old > 0 ? 0.8 * old + 0.2 * now : now; }

    glm::ivec2 render_size(glm::ivec2 fb) const {
        return glm::max(glm::ivec2(1), glm::ivec2(glm::round(glm::vec2(fb) * o_.render_scale)));
    }

    void create_renderer(glm::ivec2 size) {
        scene_.camera = fly_.camera(size.x, size.y);
        renderer_ = std::make_unique<Renderer>(*display_context_.context, scene_, settings_);
        pacer_.forget();
        clear_error();
    }

    // A new film only: the scene stays on the device and the kernels stay
    // built. The old film stays until the new one is made, so that a failure
    // (too large for the device, say) leaves a working viewer at the old size.
    void resize_renderer(glm::ivec2 size) {
        renderer_->resize(fly_.camera(size.x, size.y));
        pacer_.forget();
        denoiser_->restart(*renderer_);
        clear_error();
    }

    void step(float dt) {
        WindowInput in = window_.poll(hud_->wants_mouse());
        const ScriptRunner::Step scripted =
            script_.next_frame(renderer_->stats().samples_per_pixel, denoiser_->caught_up(*renderer_));
        MotionInput motion{glm::vec3(0), in.drag, in.scroll};
        for (const std::string& key : in.pressed) press(key);
        for (const ScriptCommand& c : scripted.commands) run_command(c, motion, in.held);
        if (in.click) focus_at(*in.click);
        in.held.insert(in.held.end(), scripted.held.begin(), scripted.held.end());
        for (const std::string& k : in.held) {
            motion.move += glm::vec3(k == "d" ? 1 : k == "a" ? -1 : 0, k == "e" ? 1 : k == "q" ? -1 : 0,
                                     k == "w" ? 1 : k == "s" ? -1 : 0);
        }
        motion.move = glm::clamp(motion.move, -1.0f, 1.0f);
        const glm::ivec2 fb = window_.framebuffer_size();
        if (fb.x <= 0 || fb.y <= 0) {  // minimised: nothing to draw
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            return;
        }
        follow_window_size(fb);
        const float radians_per_pixel = glm::radians(renderer_->camera().vfov_degrees) / float(fb.y);
        if (fly_.update(motion, dt, radians_per_pixel)) camera_changed();
        render();
        draw(fb);
        log_frame();
    }

    void follow_window_size(glm::ivec2 fb) {
        const glm::ivec2 want = render_size(fb);
        const Camera& cam = renderer_->camera();
        if (want == glm::ivec2(cam.width, cam.height)) {
            pending_size_ = glm::ivec2(0);
            return;
        }
        if (want != pending_size_) {
            pending_size_ = want;
            pending_since_ = Clock::now();
        } else if (seconds_since(pending_since_) >= kResizeSettleSeconds) {
            try {
                resize_renderer(want);
            } catch (const Error& e) {
                // Too large for the device, say: keep going at the old size.
                set_error(std::string("cannot render at the new window size: ") + e.what());
            }
            pending_size_ = glm::ivec2(0);
        }
    }

    void camera_changed() {
        const Camera& cur = renderer_->camera();
        try {
            renderer_->set_camera(fly_.camera(cur.width, cur.height));
            denoiser_->restart(*renderer_);
            clear_error();
        } catch (const Error& e) {
            set_error(e.what());
        }
    }

    // A click: the plane in focus goes through the surface under the cursor
    // (a pinhole keeps the distance too, for the camera snippet of key C).
    void focus_at(glm::vec2 window_pixel) {
        const Camera& cam = renderer_->camera();
        const auto p = window_to_image(window_pixel, window_.framebuffer_per_window_pixel(), window_.framebuffer_size(),
                                       image_rect_, {cam.width, cam.height});
        if (!p) return;
        const auto d = focus_distance_at(scene_.vertices, cam, *p);
        log_.write({{"event", "focus"}, {"frame", frame_}, {"pixel", {p->x, p->y}},
                    {"focus_distance", d ? json(*d) : json(nullptr)}});
        if (!d) {
            std::fprintf(stderr, "clpath: viewer: no surface under the cursor to focus on\n");
            return;
        }
        std::fprintf(stderr, "clpath: viewer: focus distance %g\n", double(*d));
        fly_.set_focus_distance(*d);
        camera_changed();
    }

    void set_integrator(std::uint32_t integrator) {
        if (integrator == settings_.integrator) return;
        settings_.integrator = integrator;
        std::fprintf(stderr, "clpath: viewer: integrator %s\n", integrator_name(integrator));
        try {
            renderer_->set_settings(settings_);
            renderer_->reset();
            denoiser_->restart(*renderer_);
            clear_error();
        } catch (const Error& e) {
            set_error(e.what());
        }
        pacer_.forget();  // another integrator costs another amount per sample
    }

    void set_bvh_depth(int depth) {
        bvh_depth_ = std::clamp(depth, 0, bvh_levels_);
        if (bvh_depth_ > 0) {
            remembered_bvh_depth_ = bvh_depth_;
            overlay_->set_boxes(bvh_boxes(renderer_->bvh_nodes(), bvh_depth_));
        }
    }

    void press(const std::string& key) {
        const auto bound = action_for_key(key);
        if (!bound) return;
        switch (bound->action) {
            case Action::Quit: quit_ = true; break;
            case Action::SetIntegrator: set_integrator(bound->arg); break;
            case Action::NextIntegrator: set_integrator((settings_.integrator + 1) % CLP_INTEGRATOR_COUNT); break;
            case Action::ToggleBvhOverlay: set_bvh_depth(bvh_depth_ ? 0 : remembered_bvh_depth_); break;
            case Action::BvhDeeper: set_bvh_depth(bvh_depth_ ? bvh_depth_ + 1 : remembered_bvh_depth_); break;
            case Action::BvhShallower: set_bvh_depth(std::max(1, (bvh_depth_ ? bvh_depth_ : remembered_bvh_depth_) - 1)); break;
            case Action::ExposureUp: exposure_ *= std::sqrt(2.0f); break;
            case Action::ExposureDown: exposure_ /= std::sqrt(2.0f); break;
            case Action::Screenshot: screenshot(""); break;
            case Action::CaptureWindow: {
                std::error_code ec;  // a failure shows when the capture is written
                std::filesystem::create_directories(o_.screenshot_dir, ec);
                capture_path_ = (std::filesystem::path(o_.screenshot_dir) / (default_stem() + "-window.png")).string();
                break;
            }
            case Action::PrintCamera: print_camera(); break;
            case Action::ResetCamera:
                fly_.reset();
                camera_changed();
                break;
            case Action::ToggleHud: hud_->toggle(); break;
            case Action::ToggleDenoise: denoiser_->toggle(*display_context_.context, *renderer_); break;
        }
    }

    void run_command(const ScriptCommand& c, MotionInput& motion, std::vector<std::string>& held) {
        using K = ScriptCommand::Kind;
        switch (c.kind) {
            case K::Key:
                if (is_movement_key(c.text))
                    held.push_back(c.text);  // a tap moves for one frame
                else
                    press(c.text);
                break;
            case K::Drag: motion.drag += glm::vec2(float(c.a), float(c.b)); break;
            case K::Scroll: motion.scroll += float(c.a); break;
            case K::Click: focus_at(glm::vec2(float(c.a), float(c.b))); break;
            case K::Screenshot: screenshot(c.text); break;
            case K::Capture: capture_path_ = c.text; break;
            case K::Resize: window_.resize(int(c.a), int(c.b)); break;
            case K::Camera: print_camera(); break;
            case K::Quit: quit_ = true; break;
            case K::Wait: case K::WaitSpp: case K::WaitDenoised: case K::Hold: break;  // the runner handles these
        }
    }

    std::string default_stem() const {
        return screenshot_stem(scene_.name, integrator_name(settings_.integrator), renderer_->stats().samples_per_pixel);
    }

    void screenshot(const std::string& stem) {
        // With denoising on, the denoised twin of this very estimate is saved
        // beside it; if denoising fails, the estimate is still saved.
        std::optional<Image> denoised;
        try {
            denoised = denoiser_->denoise_now(*renderer_);
        } catch (const Error& e) {
            set_error(e.what());
        }
        try {
            const auto files = save_screenshot(*renderer_, o_.screenshot_dir, stem.empty() ? default_stem() : stem,
                                               exposure_, denoised ? &*denoised : nullptr);
            for (const auto& f : files) std::fprintf(stderr, "clpath: wrote %s\n", f.c_str());
            log_.write({{"event", "screenshot"}, {"frame", frame_}, {"spp", renderer_->stats().samples_per_pixel},
                        {"files", files}});
        } catch (const Error& e) {
            set_error(e.what());
        }
    }

    void print_camera() {
        const std::string s = camera_snippet(renderer_->camera());
        std::printf("%s\n", s.c_str());
        std::fflush(stdout);
        log_.write({{"event", "camera"}, {"frame", frame_}, {"snippet", s}});
    }

    void render() {
        const std::uint64_t spp = renderer_->stats().samples_per_pixel;
        const bool done = o_.max_spp && spp >= o_.max_spp;
        samples_this_frame_ = 0;
        rays_this_frame_ = 0;
        added_spp_ = 0;
        if (render_blocked_ || done) {
            // Nothing to add: do not spin the CPU, but stay responsive.
            std::this_thread::sleep_for(std::chrono::duration<double>(pacer_.budget() / 2));
        } else {
            std::uint32_t n = pacer_.next_samples();
            if (o_.max_spp) n = std::uint32_t(std::min<std::uint64_t>(n, o_.max_spp - spp));
            const std::uint64_t rays0 = renderer_->stats().rays;
            const auto t0 = Clock::now();
            try {
                renderer_->add_samples(n);
                pacer_.record(n, seconds_since(t0));
                added_spp_ = n;
                const Camera& c = renderer_->camera();
                samples_this_frame_ = double(n) * c.width * c.height;
                rays_this_frame_ = double(renderer_->stats().rays - rays0);
            } catch (const Error& e) {
                set_error(e.what());
                render_blocked_ = true;  // until a camera or setting change: retrying would fail the same way
            }
        }
        const std::uint64_t now_spp = renderer_->stats().samples_per_pixel;
        denoiser_->update(*renderer_, render_blocked_ || (o_.max_spp && now_spp >= o_.max_spp));
        try {
            const Camera& c = renderer_->camera();
            if (const auto* denoised = denoiser_->shown(exposure_))
                display_->upload(*denoised, {c.width, c.height});
            else
                display_->upload(*renderer_, exposure_);
        } catch (const Error& e) {
            set_error(e.what());
        }
    }

    void draw(glm::ivec2 fb) {
        const glm::ivec4 rect = display_->draw(fb);
        image_rect_ = rect;
        if (bvh_depth_ > 0) overlay_->draw(renderer_->camera(), rect, {1e-4f * diagonal_, 1e4f * diagonal_});
        if (hud_->visible()) hud_->draw(hud_state());
        if (!capture_path_.empty()) {
            try {
                save_window_capture(capture_path_, fb);
                std::fprintf(stderr, "clpath: wrote %s\n", capture_path_.c_str());
                log_.write({{"event", "capture"}, {"frame", frame_}, {"file", capture_path_}});
            } catch (const Error& e) {
                set_error(e.what());
            }
            capture_path_.clear();
        }
        window_.swap();
    }

    HudState hud_state() {
        const double seconds = frame_ms_ > 0 ? frame_ms_ / 1000.0 : 1.0;
        samples_rate_ = smooth(samples_rate_, samples_this_frame_ / seconds * 1e-6);
        rays_rate_ = smooth(rays_rate_, rays_this_frame_ / seconds * 1e-6);
        HudState s;
        s.scene = scene_.name;
        s.device = device_.name;
        s.integrator = integrator_name(settings_.integrator);
        s.display_path = display_->shared() ? "CL/GL sharing" : "read-back";
        s.error = error_;
        s.spp = renderer_->stats().samples_per_pixel;
        s.max_spp = o_.max_spp;
        s.triangles = renderer_->triangle_count();
        s.width = renderer_->camera().width;
        s.height = renderer_->camera().height;
        s.ms_per_frame = frame_ms_;
        s.msamples_per_s = samples_rate_;
        s.mrays_per_s = rays_rate_;
        s.exposure = exposure_;
        s.speed = fly_.speed();
        s.bvh_depth = bvh_depth_;
        s.bvh_levels = bvh_levels_;
        const Camera& c = renderer_->camera();
        s.aperture_radius = c.aperture_radius;
        s.focus_distance = c.resolved_focus_distance();
        const DenoiseStatus d = denoiser_->status(*renderer_);
        s.denoise = d.message;
        s.denoise_problem = d.problem;
        return s;
    }

    void log_frame() {
        if (!log_) return;
        const Camera& c = renderer_->camera();
        log_.write({{"frame", frame_},
                    {"spp", renderer_->stats().samples_per_pixel},
                    {"added_spp", added_spp_},  // spp == added_spp: this frame restarted the mean
                    {"integrator", integrator_name(settings_.integrator)},
                    {"exposure", exposure_},
                    {"bvh_depth", bvh_depth_},
                    {"hud", hud_->visible()},
                    {"width", c.width},
                    {"height", c.height},
                    {"camera", {{"eye", vec_json(c.eye)}, {"target", vec_json(c.target)}, {"up", vec_json(c.up)},
                                {"vfov", c.vfov_degrees}, {"aperture_radius", c.aperture_radius},
                                {"focus_distance", c.resolved_focus_distance()}}},
                    {"frame_ms", frame_ms_},
                    {"denoise", denoise_json()},
                    {"error", error_}});
    }

    json denoise_json() const {
        const DenoiseStatus d = denoiser_->status(*renderer_);
        return {{"state", d.state},
                {"shown_spp", d.shown_spp ? json(*d.shown_spp) : json(nullptr)},  // null: the raw estimate is shown
                {"ms", d.milliseconds},
                {"message", d.message}};
    }

    void set_error(const std::string& message) {
        if (message != error_) std::fprintf(stderr, "clpath: viewer: %s\n", message.c_str());
        error_ = message;
    }
    void clear_error() {
        error_.clear();
        render_blocked_ = false;
    }

    const ViewerOptions& o_;
    RenderSettings settings_;  // filled by load_for_viewer, before scene_ (declared first)
    Scene scene_;
    ScriptRunner script_;
    DeviceInfo device_;
    float diagonal_;
    SigintFlag sigint_;
    // Declared in the order they must be made; torn down in reverse, GL and
    // OpenCL objects before the context and window that own them.
    Window window_;
    DisplayContext display_context_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<Display> display_;
    std::unique_ptr<BvhOverlay> overlay_;
    std::unique_ptr<Hud> hud_;
    std::unique_ptr<ViewDenoiser> denoiser_;
    FlyCamera fly_;
    FramePacer pacer_;
    StateLog log_;

    float exposure_;
    int bvh_depth_ = 0, remembered_bvh_depth_ = kDefaultBvhDepth, bvh_levels_ = 0;
    std::string error_, capture_path_;
    bool render_blocked_ = false, quit_ = false;
    long frame_ = 0;
    std::uint32_t added_spp_ = 0;
    double frame_ms_ = 0, samples_this_frame_ = 0, rays_this_frame_ = 0, samples_rate_ = 0, rays_rate_ = 0;
    glm::ivec2 pending_size_{0};
    glm::ivec4 image_rect_{0};  // where the last frame drew the image
    Clock::time_point pending_since_;
};

}  // namespace

int run_viewer(const ViewerOptions& options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace clpath
