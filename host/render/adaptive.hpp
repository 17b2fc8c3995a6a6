#pragma once
// Adaptive sampling to a noise target: pixels whose estimated error is below
// the target stop taking samples; the render ends when none is left.
//
// The estimate is the one Cycles uses (after Dammertz, Hanika, Keller and
// Lensch 2010, "A hierarchical automatic stopping condition for Monte Carlo
// global illumination", sec. 2.1): besides the image I (the mean of all of a
// pixel's samples) the film keeps a second image A, the mean of its
// odd-indexed samples only (kernels: the film's w lanes, summing r+g+b). I - A
// is half the difference of the even and the odd half's means, whose size is
// that of the standard error of I; it is scaled by the square root of the
// pixel's value (the Cycles normalisation, so that R means what Cycles' "noise
// threshold" means):
//     error = |sum_c I_c - sum_c A_c| / (1e-4 + sqrt(sum_c I_c)).
// A pixel is converged when error < R; every pixel next to an unconverged
// one (3x3) samples on too, as Cycles' filter does, so that a feature seen by
// one pixel is not left to it alone.
//
// Decisions are made between passes, fixed groups of whole chunks
// (kAdaptivePassChunks), from the exact film (render/exact_film.hpp) holding
// exactly the passes before: the mask of a pass is a function of those sums,
// the sample counts and the target alone, so a render over many devices takes
// the same decisions, and gives the same bits, as one device.
#include <cstdint>
#include <vector>

#include "render/exact_film.hpp"

namespace clpath {

// Chunks a pass holds: a pass is the unit of decision, so that several
// devices have chunks to share between two decisions.
constexpr std::uint32_t kAdaptivePassChunks = 4;

// The samples every pixel takes before any may stop: at least 16 and
// 4 / sqrt(target), so that a pixel is not judged on a handful of samples
// that all missed a rare path.
std::uint64_t adaptive_min_samples(double noise_target);

// The error estimate above of one pixel; infinity where it has no sample
// or no half film.
double adaptive_pixel_error(const ExactFilm& film, std::size_t pixel);

// The pixels of the next pass: 1 where a pixel samples on. A pixel with fewer
// than min_samples samples always does; otherwise one whose error, or any
// 8-neighbour's, is at or above the target. Needs the film's half film and
// per-pixel counts.
std::vector<std::uint8_t> adaptive_active_pixels(const ExactFilm& film, double noise_target,
                                                 std::uint64_t min_samples);

}  // namespace clpath
