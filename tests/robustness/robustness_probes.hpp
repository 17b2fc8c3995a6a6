#pragma once
// The program of tests/robustness/robustness_probes.cl, built with every
// feature on and cached like any program.
#include "render/kernel_features.hpp"
#include "render/kernel_programs.hpp"
#include "support/test_device.hpp"

namespace clpath::test {

inline cl_program robustness_program() {
    RenderSettings all;
    all.all_features = true;
    return test_program("robustness_probes.cl",
                        build_options(kernel_features(SceneFeatures{}, all)) + layout_options(node_layout()));
}

}  // namespace clpath::test
