#pragma once
// The schedule of an adaptive render (render/adaptive.hpp) as render_session()
// (render/render_session.hpp) runs it: the pass open, its mask, and each pixel's sample count.
// Pass q is chunks [q * kAdaptivePassChunks, (q + 1) * kAdaptivePassChunks)
// of the plan; its mask is decided from the film holding exactly the passes
// before it, so it does not depend on which device rendered what.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "render/adaptive.hpp"
#include "render/chunks.hpp"
#include "render/exact_film.hpp"

namespace clpath {

class AdaptivePasses {
public:
    // Throws clpath::Error for chunks of an odd number of samples (the half
    // film needs as many odd samples as even ones in every pixel).
    // rule: replaces adaptive_active_pixels (tests: a biased rule); empty: that.
    using Rule = std::function<std::vector<std::uint8_t>(const ExactFilm&, std::uint64_t min_samples)>;
    AdaptivePasses(const ChunkPlan& plan, double noise_target, int width, int height, Rule rule = {});

    // Continues from a checkpoint's film (its half film and per-pixel counts)
    // and chunks, which must end at a pass boundary (clpath::Error otherwise).
    void resume(const ExactFilm& film, const std::vector<std::uint64_t>& done);

    std::uint64_t pass() const { return pass_; }
    std::shared_ptr<const std::vector<std::uint8_t>> mask() const { return mask_; }
    // Nothing more to render: every pixel met the target, or the plan's chunks are all done.
    bool converged() const { return converged_; }
    bool ended() const { return ended_; }
    std::uint64_t min_samples() const { return min_samples_; }
    // Chunks in a pass (fewer in the plan's last; 0 past its end).
    std::uint64_t chunks_in(std::uint64_t pass) const;

    // The open pass is complete and `film` (a snapshot) holds exactly the
    // passes up to it: counts its samples, sets film's per-pixel counts and
    // decides the next pass's mask. True when a next pass opens (pass() and
    // mask() are then its); false when the render is over (converged() or ended()).
    bool finish_pass(ExactFilm& film);

    // Each pixel's samples in a film holding `done` (the open pass partly
    // rendered: an interrupted or timed-out render).
    std::vector<std::uint32_t> counts_with(const std::vector<std::uint64_t>& done) const;

private:
    void decide(const ExactFilm& film);

    ChunkPlan plan_;
    Rule rule_;
    double target_;
    std::uint64_t min_samples_;
    std::size_t pixels_;
    std::uint64_t pass_ = 0;
    bool converged_ = false, ended_ = false;
    std::vector<std::uint32_t> counts_;  // samples per pixel before the open pass (all passes when over)
    std::shared_ptr<const std::vector<std::uint8_t>> mask_;
};

}  // namespace clpath
