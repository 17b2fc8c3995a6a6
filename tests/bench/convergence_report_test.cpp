// The convergence benchmark's arithmetic: time to a PSNR, efficiency, the CSV
// and the reduced reference, against values worked out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "bench/convergence.hpp"
#include "bench/convergence_report.hpp"
#include "bench/estimator_configs.hpp"
#include "util/error.hpp"

using namespace clpath;

namespace {
ConvergencePoint point(std::uint64_t spp, double seconds, double psnr) {
    ConvergencePoint p;
    p.spp = spp;
    p.seconds = seconds;
    p.error.psnr = psnr;
    p.error.mse = std::pow(10.0, -psnr / 10);
    p.error.rmse = std::sqrt(p.error.mse);
    return p;
}
}  // namespace

// Between (1 s, 28 dB) and (4 s, 34 dB), 30 dB is a third of the way in
// PSNR, so a third of the way in log time: 4^(1/3) s.
TEST(ConvergenceReport, TimeToReachInterpolatesInLogTime) {
    const std::vector<ConvergencePoint> pts{point(1, 0.5, 20), point(2, 1, 28), point(4, 4, 34)};
    const TimeToReach t = time_to_reach(pts, 30);
    ASSERT_TRUE(t.reached);
    EXPECT_FALSE(t.at_first_point);
    EXPECT_NEAR(t.seconds, std::cbrt(4.0), 1e-12);
    EXPECT_FALSE(time_to_reach(pts, 35).reached);
    const TimeToReach first = time_to_reach(pts, 10);
    EXPECT_TRUE(first.at_first_point);
    EXPECT_EQ(first.seconds, 0.5);
    // A later dip below the level does not move the first crossing.
    const std::vector<ConvergencePoint> dip{point(1, 1, 29), point(2, 2, 31), point(4, 4, 29.5), point(8, 8, 33)};
    EXPECT_NEAR(time_to_reach(dip, 30).seconds, std::sqrt(2.0), 1e-12);
}

TEST(ConvergenceReport, EfficiencyAndTable) {
    ConvergenceSeries a{"thesis", "base", "integrator=path-bsdf", {point(1, 1, 20), point(2, 2, 23)}};
    ConvergenceSeries b{"clpath", "default", "integrator=path", {point(1, 1, 30), point(2, 2, 33)}};
    EXPECT_NEAR(efficiency(a), 1.0 / (std::pow(10.0, -2.3) * 2), 1e-9);
    EXPECT_NEAR(efficiency(b) / efficiency(a), 10.0, 1e-9);
    const std::string md = convergence_markdown({a, b}, {30, 35, 40});
    EXPECT_NE(md.find("| to 30 dB | to 35 dB | to 40 dB | efficiency vs thesis |"), std::string::npos) << md;
    EXPECT_NE(md.find("| thesis | base | 2 | 2 s | 23.00 | not reached | not reached | not reached | 1 |"),
              std::string::npos) << md;
    EXPECT_NE(md.find("| clpath | default | 2 | 2 s | 33.00 | ≤ 1 s | not reached | not reached | 10 |"),
              std::string::npos) << md;
    const std::string csv = convergence_csv("box", {a});
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "scene,config,options,spp,seconds,rmse,psnr,mse,relmse");
    EXPECT_NE(csv.find("\nbox,thesis,integrator=path-bsdf,2,2,"), std::string::npos) << csv;
}

// A 2x reduction averages 2x2 blocks; sizes that are no integer multiple fail
// with a message naming the file.
TEST(ConvergenceReport, ReferenceReducedByBlockMeans) {
    Image ref;
    ref.width = 4;
    ref.height = 2;
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c) ref.rgb.push_back(float(i + c));
    const Image r = reference_at(ref, 2, 1, "ref.exr");
    ASSERT_EQ(r.width, 2);
    ASSERT_EQ(r.height, 1);
    EXPECT_FLOAT_EQ(r.at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(r.at(1, 0, 2), (2 + 3 + 6 + 7) / 4.0f + 2);
    EXPECT_EQ(reference_at(ref, 4, 2, "ref.exr").rgb, ref.rgb);
    try {
        reference_at(ref, 3, 2, "ref.exr");
        ADD_FAILURE() << "3x2 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ref.exr: reference is 4x2"), std::string::npos) << e.what();
    }
}

// Every option the standard configurations use applies; unknown names and bad values throw.
TEST(EstimatorConfigs, OptionsApply) {
    for (const auto& c : estimator_configs())
        for (const auto& [name, value] : c.options) {
            RenderSettings s;
            EXPECT_NO_THROW(apply_render_option(s, name, value)) << c.name << ": " << name << "=" << value;
        }
    RenderSettings s;
    apply_render_option(s, "hemisphere", "uniform");
    EXPECT_EQ(s.hemisphere, kHemisphereUniform);
    apply_render_option(s, "accel", "flat");
    EXPECT_EQ(s.accel, Accel::Flat);
    EXPECT_THROW(apply_render_option(s, "rr", "sometimes"), Error);
    EXPECT_THROW(apply_render_option(s, "antialiasing", "on"), Error);
    EXPECT_EQ(estimator_configs().front().name, "thesis");
    EXPECT_EQ(estimator_configs().back().name, "clpath");
}
