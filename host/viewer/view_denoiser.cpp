#include "viewer/view_denoiser.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "image/tone_map.hpp"
#include "render/settings.hpp"
#include "shared_structs.h"
#include "util/error.hpp"

namespace clpath::viewer {
namespace {

using Clock = std::chrono::steady_clock;

double now_seconds() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

}  // namespace

ViewDenoiser::~ViewDenoiser() {
    if (job_.valid()) job_.wait();  // the job uses denoiser_ and the guides it holds
}

bool ViewDenoiser::applies(const Renderer& renderer) const {
    // The network is trained on radiance; the debug views (normals, depth,
    // albedo, heatmap) are no pictures of light and are shown as they are.
    const std::uint32_t i = renderer.settings().integrator;
    return i == CLP_INTEGRATOR_PATH || i == CLP_INTEGRATOR_PATH_BSDF || i == CLP_INTEGRATOR_AO;
}

void ViewDenoiser::toggle(Context& ctx, const Renderer& renderer) {
    if (on_) {
        on_ = false;
        return;
    }
    if (!unavailable_.empty()) {
        std::fprintf(stderr, "clpath: viewer: cannot denoise: %s\n", unavailable_.c_str());
        return;
    }
    try {
        if (!denoiser_) {
            denoiser_ = std::make_unique<Denoiser>();
            std::fprintf(stderr, "clpath: viewer: denoising with %s\n", denoiser_->library_path().c_str());
        }
        if (!guides_) guides_ = std::make_unique<GuidePasses>(ctx, renderer);
    } catch (const Error& e) {
        // Nothing else changes: the estimate is shown, as before the key.
        unavailable_ = e.what();
        std::fprintf(stderr, "clpath: viewer: cannot denoise: %s\n", unavailable_.c_str());
        return;
    }
    on_ = true;
    // Off and on again over the same view keeps its guides and denoised image.
    if (guides_for_ != generation_) restart_guides(renderer);
}

void ViewDenoiser::restart(const Renderer& renderer) {
    ++generation_;  // a denoise in flight is of the old view: its result is dropped
    pacing_.reset();
    guide_pacer_.forget();
    shown_.reset();
    failure_.clear();
    if (on_) restart_guides(renderer);  // else when it is next turned on
}

void ViewDenoiser::restart_guides(const Renderer& renderer) {
    guides_for_ = generation_;
    try {
        guides_->restart(renderer);
    } catch (const Error& e) {
        failure_ = std::string("the denoiser's guides: ") + e.what();
    }
}

void ViewDenoiser::show(Result r) {
    if (r.generation != generation_) return;  // stale: the view changed while it ran
    pacing_.finished(now_seconds(), r.seconds);
    if (!r.error.empty()) {
        failure_ = r.error;
        std::fprintf(stderr, "clpath: viewer: %s\n", failure_.c_str());
        return;
    }
    shown_ = std::move(r);
    srgb_stale_ = true;
}

void ViewDenoiser::collect(bool wait) {
    if (!job_.valid()) return;
    if (!wait && job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    show(job_.get());
}

void ViewDenoiser::update(Renderer& renderer, bool final) {
    collect(false);
    // While the camera moves every frame, guides would be thrown away unused:
    // they start once a view has held for a frame.
    const bool held = generation_ == updated_generation_;
    updated_generation_ = generation_;
    if (!on_ || !applies(renderer) || !failure_.empty()) return;
    try {
        if (!guides_->ready()) {
            if (!held) return;
            const auto t0 = Clock::now();
            const std::uint32_t n = guides_->advance(renderer, guide_pacer_.next_samples());
            guide_pacer_.record(n, std::chrono::duration<double>(Clock::now() - t0).count());
            if (!guides_->ready()) return;
        }
        const std::uint64_t spp = renderer.stats().samples_per_pixel;
        if (job_.valid() || !pacing_.due(now_seconds(), spp, final)) return;
        Image color = renderer.resolve(1.0f).linear;
        pacing_.started(spp);
        job_ = std::async(std::launch::async, [this, color = std::move(color), guides = guides_->guides(), spp,
                                               generation = generation_] {
            Result r;
            r.spp = spp;
            r.generation = generation;
            const auto t0 = Clock::now();
            try {
                r.image = denoiser_->denoise(color, guides.get());
            } catch (const Error& e) {
                r.error = e.what();
            }
            r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
            return r;
        });
    } catch (const Error& e) {
        failure_ = e.what();
        std::fprintf(stderr, "clpath: viewer: denoising: %s\n", failure_.c_str());
    }
}

const std::vector<std::uint8_t>* ViewDenoiser::shown(float exposure) {
    if (!on_ || !shown_) return nullptr;
    if (srgb_stale_ || exposure != shown_exposure_) {
        DisplaySettings d;
        d.exposure_stops = std::log2(exposure);
        shown_srgb_ = display_srgb8(shown_->image, d);
        shown_exposure_ = exposure;
        srgb_stale_ = false;
    }
    return &shown_srgb_;
}

std::optional<Image> ViewDenoiser::denoise_now(Renderer& renderer) {
    if (!on_ || !applies(renderer)) return std::nullopt;
    collect(true);
    if (!failure_.empty()) throw Error("denoising: " + failure_);
    while (!guides_->ready()) guides_->advance(renderer, std::uint32_t(GuidePasses::total()));
    Result r;
    r.spp = renderer.stats().samples_per_pixel;
    r.generation = generation_;
    const auto t0 = Clock::now();
    r.image = denoiser_->denoise(renderer.resolve(1.0f).linear, guides_->guides().get());
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    pacing_.started(r.spp);
    Image out = r.image;
    show(std::move(r));  // and it is what the window shows from now on
    return out;
}

bool ViewDenoiser::caught_up(const Renderer& renderer) const {
    if (!on_ || !applies(renderer) || !failure_.empty()) return true;
    return shown_ && shown_->spp == renderer.stats().samples_per_pixel;
}

DenoiseStatus ViewDenoiser::status(const Renderer& renderer) const {
    DenoiseStatus s;
    if (!unavailable_.empty()) {
        s.state = "unavailable";
        // Its first line (what is missing); the whole message, with what was
        // tried and how to install it, went to the terminal.
        std::string first = unavailable_.substr(0, unavailable_.find('\n'));
        if (!first.empty() && first.back() == ':') first.pop_back();
        s.message = first + " (the terminal says what was tried)";
        s.problem = true;
        return s;
    }
    if (!on_) {
        s.state = "off";
        s.message = "off (N)";
        return s;
    }
    s.state = "on";
    if (!failure_.empty()) {
        s.message = "denoising failed: " + failure_;
        s.problem = true;
    } else if (!applies(renderer)) {
        s.message = std::string("not for the ") + integrator_name(renderer.settings().integrator) + " view";
    } else if (!guides_->ready()) {
        s.message = "guides " + std::to_string(guides_->done()) + " / " + std::to_string(GuidePasses::total()) + " spp";
    } else if (!shown_) {
        s.message = "denoising...";
    }
    if (shown_ && applies(renderer)) {
        s.shown_spp = shown_->spp;
        s.milliseconds = 1000.0 * shown_->seconds;
        const double mp = double(shown_->image.width) * shown_->image.height * 1e-6;
        char line[160];
        std::snprintf(line, sizeof line, "on, of %llu spp: %.0f ms (%.2f s/MP)", (unsigned long long)shown_->spp,
                      s.milliseconds, mp > 0 ? shown_->seconds / mp : 0.0);
        if (s.message.empty()) s.message = line;
    }
    return s;
}

}  // namespace clpath::viewer
