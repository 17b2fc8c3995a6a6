#include "bench/convergence_report.hpp"

#include <cmath>
#include <cstdio>

namespace clpath {
namespace {
std::string format(const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::string seconds_text(double s) { return s < 10 ? format("%.3g s", s) : format("%.0f s", s); }
}  // namespace

TimeToReach time_to_reach(const std::vector<ConvergencePoint>& points, double target) {
    TimeToReach r;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double p1 = points[i].error.psnr;
        if (!(p1 >= target)) continue;
        r.reached = true;
        if (i == 0) {
            r.at_first_point = true;
            r.seconds = points[0].seconds;
            return r;
        }
        const double p0 = points[i - 1].error.psnr;
        const double t0 = std::log(points[i - 1].seconds), t1 = std::log(points[i].seconds);
        const double f = p1 > p0 ? (target - p0) / (p1 - p0) : 1.0;
        r.seconds = std::exp(t0 + f * (t1 - t0));
        return r;
    }
    return r;
}

double efficiency(const ConvergenceSeries& s) {
    if (s.points.empty()) return 0;
    const auto& p = s.points.back();
    return p.error.mse > 0 && p.seconds > 0 ? 1.0 / (p.error.mse * p.seconds) : 0;
}

std::string convergence_csv(const std::string& scene, const std::vector<ConvergenceSeries>& series) {
    std::string out = "scene,config,options,spp,seconds,rmse,psnr,mse,relmse\n";
    char buf[256];
    for (const auto& s : series)
        for (const auto& p : s.points) {
            std::snprintf(buf, sizeof buf, ",%llu,%.6g,%.6g,%.4f,%.6g,%.6g\n", (unsigned long long)p.spp, p.seconds,
                          p.error.rmse, p.error.psnr, p.error.mse, p.error.relmse);
            out += scene + "," + s.config + "," + s.options + buf;
        }
    return out;
}

std::string convergence_markdown(const std::vector<ConvergenceSeries>& series, const std::vector<double>& levels) {
    std::string out = "| configuration | change | spp | time | PSNR |";
    for (double l : levels) out += format(" to %.0f dB |", l);
    out += " efficiency vs " + (series.empty() ? std::string("-") : series[0].config) + " |\n|---|---|--:|--:|--:|";
    for (std::size_t i = 0; i < levels.size(); ++i) out += "--:|";
    out += "--:|\n";
    const double base = series.empty() ? 0 : efficiency(series[0]);
    for (const auto& s : series) {
        out += "| " + s.config + " | " + s.description + " | ";
        if (s.points.empty()) {
            out += "- | - | - |";
            for (std::size_t i = 0; i < levels.size(); ++i) out += " - |";
            out += " - |\n";
            continue;
        }
        const auto& last = s.points.back();
        out += std::to_string(last.spp) + " | " + seconds_text(last.seconds) + " | " + format("%.2f", last.error.psnr) +
               " |";
        for (double l : levels) {
            const TimeToReach t = time_to_reach(s.points, l);
            out += " ";
            out += !t.reached ? std::string("not reached") : std::string(t.at_first_point ? "≤ " : "") + seconds_text(t.seconds);
            out += " |";
        }
        out += base > 0 ? format(" %.3g |\n", efficiency(s) / base) : std::string(" - |\n");
    }
    return out;
}

}  // namespace clpath
