#pragma once
// A variant of the kernels timed against the built-in ones, launch by launch
// in one process (bench rays --ab-kernels, bench render-ab): the pairs'
// speed ratios, and how much of the output differs.
#include <cstddef>
#include <string>
#include <vector>

namespace clpath {

struct AbResult {
    bool ran = false;
    std::vector<double> ratios;        // per launch pair: built-in time / variant time (> 1: the variant is faster)
    double median = 0, q1 = 0, q3 = 0;  // of ratios
    std::size_t differing = 0;         // outputs (rays, pixels) that differ, bit for bit, from the built-in kernels'
};

// Sets median and quartiles of ab.ratios (interpolated between order
// statistics) and ran; ratios must not be empty.
void finish_ab(AbResult& ab);

// "variant/built-in 1.030 (quartiles 0.990-1.050) over 10 launch pairs"
std::string describe_ab_ratios(const AbResult& ab);

}  // namespace clpath
