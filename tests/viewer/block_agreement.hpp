#pragma once
// Does an image agree with independent renders of the same view? Compares
// the means of 8x8 blocks. For each block and channel, K reference renders
// of n spp give a mean and a sample variance; the candidate (N spp) differs
// from the references' mean by a t-distributed amount with K-1 degrees of
// freedom when both estimate the same image:
//     t = (v - mean) / sqrt(s^2 * (n/N + 1/K)).
// Each t becomes an exact normal z through its p-value, so the blocks' sum of
// z^2 is chi-square under agreement; that and the largest |z| (Bonferroni
// over blocks) are tested at a significance chosen by the caller. No
// tolerance is tuned: all of it follows from the renders' own variance.
#include <string>
#include <vector>

#include "image/image.hpp"

namespace clpath::test {

struct BlockAgreement {
    bool agrees = true;
    double chi_square_p[3] = {1, 1, 1};  // per channel
    double largest_z = 0;                 // over blocks and channels
    double z_limit = 0;                   // Bonferroni limit for largest_z
    int blocks = 0;
    std::string report;                   // for a failure message
};

BlockAgreement compare_blocks(const Image& candidate, unsigned candidate_spp, const std::vector<Image>& references,
                              unsigned reference_spp, double alpha, int block = 8);

}  // namespace clpath::test
