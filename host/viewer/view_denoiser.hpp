#pragma once
// The viewer's denoised display (key N). The renderer keeps accumulating the
// unbiased estimate; this holds what is shown in its place: the estimate at
// some sample count, denoised by Open Image Denoise with albedo and normal
// guides of the current camera (guide_passes.hpp). Denoising runs on a worker
// thread at the rate DenoisePacing allows, so the window keeps drawing; the
// latest denoised image is shown until a newer one is ready. A camera, size
// or view change makes it stale: the raw estimate shows until the guides and a
// first denoise of the new view are done.
// Without the library the toggle changes nothing but the message it leaves
// (unavailable()), which the heads-up display shows.
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "denoise/denoiser.hpp"
#include "render/renderer.hpp"
#include "viewer/denoise_pacing.hpp"
#include "viewer/frame_pacer.hpp"
#include "viewer/guide_passes.hpp"

namespace clpath::viewer {

// What the heads-up display and the state log say about denoising.
struct DenoiseStatus {
    std::string state;    // "off", "on", "unavailable"
    std::string message;  // a line for the display (why not, or what it waits for)
    bool problem = false; // the message is an error (library missing, a failure)
    std::optional<std::uint64_t> shown_spp;  // the shown image's estimate's spp, if a denoised one is shown
    double milliseconds = 0;                 // the last denoise's own time
};

class ViewDenoiser {
public:
    // guide_budget_seconds: rendering time per frame given to the guides while they are made.
    explicit ViewDenoiser(double guide_budget_seconds) : guide_pacer_(guide_budget_seconds) {}
    ~ViewDenoiser();
    ViewDenoiser(const ViewDenoiser&) = delete;
    ViewDenoiser& operator=(const ViewDenoiser&) = delete;

    // Key N. The first time on loads the library and compiles the guide
    // views; if either fails it stays off and says why.
    void toggle(Context& ctx, const Renderer& renderer);
    bool on() const { return on_; }

    // The estimate restarted (camera, size, view): what is shown is stale.
    void restart(const Renderer& renderer);
    // Once a frame, after the estimate's samples: collects a finished
    // denoise, renders guide samples, starts a denoise when one is due.
    // final: the estimate gets no more samples.
    void update(Renderer& renderer, bool final);
    // The image to show in place of the estimate, RGBA8 sRGB at this exposure
    // (the film kernel's clamp and sRGB curve), or null: show the estimate.
    const std::vector<std::uint8_t>* shown(float exposure);
    // The estimate as it is now, denoised (a screenshot): waits for a denoise
    // in flight and finishes the guides first. Null when off or unavailable.
    std::optional<Image> denoise_now(Renderer& renderer);
    // Whether the shown image is the current estimate's (for scripts' wait-denoised):
    // true when nothing is to be waited for (off, unavailable, a debug view).
    bool caught_up(const Renderer& renderer) const;

    DenoiseStatus status(const Renderer& renderer) const;

private:
    struct Result {
        Image image;
        std::uint64_t spp = 0, generation = 0;
        double seconds = 0;
        std::string error;
    };
    void restart_guides(const Renderer& renderer);
    void collect(bool wait);
    void show(Result r);
    bool applies(const Renderer& renderer) const;  // a radiance view

    FramePacer guide_pacer_;
    DenoisePacing pacing_;
    std::unique_ptr<Denoiser> denoiser_;  // before job_: a job in flight uses it
    std::unique_ptr<GuidePasses> guides_;
    std::future<Result> job_;
    std::uint64_t generation_ = 1, guides_for_ = 0;  // the view the guides are of
    std::uint64_t updated_generation_ = 0;           // the view of the last update()
    bool on_ = false;
    std::string unavailable_, failure_;
    std::optional<Result> shown_;
    std::vector<std::uint8_t> shown_srgb_;
    float shown_exposure_ = 0;
    bool srgb_stale_ = true;
};

}  // namespace clpath::viewer
