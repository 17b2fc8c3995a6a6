#pragma once
// Convergence series measured on several MPI ranks, brought together on rank 0.
#include <vector>

#include "bench/convergence_report.hpp"
#include "bench/estimator_configs.hpp"

namespace clpath {

// Every rank passes the series it measured; rank 0 gets them all, in the order
// of `configs` (each rank measured a subset). Other ranks get an empty list.
std::vector<ConvergenceSeries> gather_series(const std::vector<ConvergenceSeries>& mine,
                                             const std::vector<EstimatorConfig>& configs);

}  // namespace clpath
