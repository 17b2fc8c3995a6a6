#pragma once
// What the convergence benchmark reports: the time each configuration needs
// to reach a PSNR, its efficiency against the baseline, as CSV and Markdown.
#include <string>
#include <vector>

#include "bench/convergence.hpp"

namespace clpath {

struct ConvergenceSeries {
    std::string config, description, options;  // options as applied in this build
    std::vector<ConvergencePoint> points;
};

struct TimeToReach {
    bool reached = false;
    bool at_first_point = false;  // already reached at 1 spp: the time is an upper bound
    double seconds = 0;
};

// The first crossing of psnr_db, interpolated between the two points around
// it linearly in (PSNR, log time): where MSE falls as 1/time, PSNR is linear
// in log time.
TimeToReach time_to_reach(const std::vector<ConvergencePoint>& points, double psnr_db);

// 1 / (MSE x time) at the series' last point (0 for an empty series).
double efficiency(const ConvergenceSeries& series);

// One row per point: scene,config,options,spp,seconds,rmse,psnr,mse,relmse.
std::string convergence_csv(const std::string& scene, const std::vector<ConvergenceSeries>& series);

// A table with one row per configuration: last point, time to each of
// psnr_levels, efficiency relative to series[0] (the baseline).
std::string convergence_markdown(const std::vector<ConvergenceSeries>& series, const std::vector<double>& psnr_levels);

}  // namespace clpath
