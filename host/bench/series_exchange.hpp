#pragma once
// Convergence series measured on several processes (MPI ranks), brought
// together on the lead.
#include <vector>

#include "bench/convergence_report.hpp"
#include "bench/estimator_configs.hpp"

namespace clpath {

class ProcessGroup;

// Every process passes the series it measured; the lead gets them all, in the
// order of `configs` (each process measured a subset). Other processes get an
// empty list. Without a group (nullptr), `mine` is all there is.
std::vector<ConvergenceSeries> gather_series(const std::vector<ConvergenceSeries>& mine,
                                             const std::vector<EstimatorConfig>& configs, ProcessGroup* group);

}  // namespace clpath
