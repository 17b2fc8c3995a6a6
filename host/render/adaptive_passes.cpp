#include "render/adaptive_passes.hpp"

#include <algorithm>

#include "util/error.hpp"

namespace clpath {

AdaptivePasses::AdaptivePasses(const ChunkPlan& plan, double noise_target, int width, int height, Rule rule)
    : plan_(plan), rule_(std::move(rule)), target_(noise_target), min_samples_(adaptive_min_samples(noise_target)),
      pixels_(std::size_t(width) * std::size_t(height)), counts_(pixels_, 0),
      mask_(std::make_shared<const std::vector<std::uint8_t>>(pixels_, std::uint8_t(1))) {
    if (plan.chunk_samples % 2)
        throw Error("adaptive sampling needs chunks of an even number of samples (--chunk " +
                    std::to_string(plan.chunk_samples) + " is odd)");
}

std::uint64_t AdaptivePasses::chunks_in(std::uint64_t pass) const {
    if (!plan_.total_samples) return kAdaptivePassChunks;
    const std::uint64_t count = plan_.chunk_count(), first = pass * kAdaptivePassChunks;
    return first >= count ? 0 : std::min<std::uint64_t>(kAdaptivePassChunks, count - first);
}

void AdaptivePasses::resume(const ExactFilm& film, const std::vector<std::uint64_t>& done) {
    // Checkpoints of adaptive renders are written between passes only.
    for (std::size_t i = 0; i < done.size(); ++i)
        if (done[i] != i) throw Error("the checkpoint's chunks do not end at a pass of the adaptive render");
    if (done.size() % kAdaptivePassChunks && chunks_in(done.size() / kAdaptivePassChunks) != done.size() % kAdaptivePassChunks)
        throw Error("the checkpoint's chunks do not end at a pass of the adaptive render");
    if (film.pixel_samples().size() != pixels_ || film.half().size() != pixels_)
        throw Error("the checkpoint holds no adaptive render's sample counts");
    counts_ = film.pixel_samples();
    pass_ = (done.size() + kAdaptivePassChunks - 1) / kAdaptivePassChunks;
    if (done.empty()) return;
    if (chunks_in(pass_) == 0) {
        ended_ = true;
        return;
    }
    decide(film);
}

void AdaptivePasses::decide(const ExactFilm& film) {
    auto mask = std::make_shared<std::vector<std::uint8_t>>(
        rule_ ? rule_(film, min_samples_) : adaptive_active_pixels(film, target_, min_samples_));
    converged_ = std::none_of(mask->begin(), mask->end(), [](std::uint8_t a) { return a != 0; });
    mask_ = std::move(mask);
}

bool AdaptivePasses::finish_pass(ExactFilm& film) {
    if (converged_ || ended_) throw Error("internal: a pass finished after the adaptive render ended");
    std::uint64_t samples = 0;
    for (std::uint64_t k = 0; k < chunks_in(pass_); ++k) samples += plan_.chunk(pass_ * kAdaptivePassChunks + k).samples;
    for (std::size_t p = 0; p < pixels_; ++p)
        if ((*mask_)[p]) counts_[p] += std::uint32_t(samples);
    if (film.half().empty()) film.half().assign(pixels_, 0);  // no device had a chunk (every pixel was stopped)
    film.set_pixel_samples(counts_);
    ++pass_;
    if (chunks_in(pass_) == 0) {
        ended_ = true;
        return false;
    }
    decide(film);
    return !converged_;
}

std::vector<std::uint32_t> AdaptivePasses::counts_with(const std::vector<std::uint64_t>& done) const {
    std::vector<std::uint32_t> counts = counts_;
    if (converged_ || ended_) return counts;
    std::uint64_t samples = 0;
    for (std::uint64_t k : done)
        if (k / kAdaptivePassChunks == pass_) samples += plan_.chunk(k).samples;
        else if (k / kAdaptivePassChunks > pass_) throw Error("internal: a chunk of a pass not yet open was rendered");
    for (std::size_t p = 0; p < pixels_; ++p)
        if ((*mask_)[p]) counts[p] += std::uint32_t(samples);
    return counts;
}

}  // namespace clpath
