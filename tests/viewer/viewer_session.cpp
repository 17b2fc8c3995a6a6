// The viewer as a user runs it: the clpath program under xvfb-run (Xvfb,
// Mesa's llvmpipe), real kernels on the test device, scripted input. Each
// test reads the viewer's state log and the images it writes.
// Built and registered by viewer_tests.cmake, which passes CLPATH_EXE,
// XVFB_RUN and VIEWER_TEST_OUT.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include "image/image.hpp"
#include "viewer/block_agreement.hpp"
#include "viewer/process.hpp"

using namespace clpath;
using namespace clpath::test;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Small images: these run on two CPU cores.
constexpr int kWidth = 64, kHeight = 48;

// xvfb-run -a takes the first display number from -n (given before -a) whose
// lock file is missing, then starts Xvfb there; two runs that look at once can
// pick the same one, and the second Xvfb fails. CTest runs these tests one at
// a time (RESOURCE_LOCK); a search starting from a number of this process's
// own keeps apart the test runs of other build folders on the same machine.
std::string xvfb_run() {
    return std::string(XVFB_RUN) + " -n " + std::to_string(100 + ::getpid() % 800) + " -a";
}

// A fresh folder per test, named after it.
std::string test_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::path(VIEWER_TEST_OUT) / info->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

struct Session {
    ProcessResult result;
    std::vector<json> log;
    std::vector<json> frames() const {
        std::vector<json> f;
        for (const auto& l : log)
            if (!l.contains("event")) f.push_back(l);
        return f;
    }
};

// Runs 'clpath view' under Xvfb with a script. --frames bounds a session that
// would otherwise wait forever (and fails it, as the script did not finish).
Session view(const std::string& dir, const std::string& script, const std::string& extra = "", int width = kWidth,
             int height = kHeight) {
    write_text(dir + "/script.txt", script);
    const std::string cmd = xvfb_run() + " -s '-screen 0 640x480x24' " + CLPATH_EXE +
                            " view --width " + std::to_string(width) + " --height " + std::to_string(height) +
                            " --frames 3000 --script " + dir + "/script.txt --state-log " + dir +
                            "/state.jsonl --screenshot-dir " + dir + " " + extra;
    Session s;
    s.result = run_shell(cmd);
    s.log = read_json_lines(dir + "/state.jsonl");
    return s;
}

Image mirrored(const Image& img) {
    Image m = img;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c)
                m.rgb[(std::size_t(y) * img.width + x) * 3 + c] = img.at(img.width - 1 - x, y, c);
    return m;
}

float srgb_encode(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

std::size_t differing_pixels(const Image& a, const Image& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.rgb.size(); i += 3)
        n += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
    return n;
}

}  // namespace

TEST(Session, RefinesEveryFrameAndACameraMoveRestartsTheMean) {
    const std::string dir = test_dir();
    const Session s = view(dir,
                           "wait-spp 3\n"
                           "hold w 2\n"  // forward for two frames
                           "wait 3\n"
                           "drag 20 -10\n"  // look right and up
                           "wait 3\n"
                           "camera\n"
                           "quit\n");
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    const auto f = s.frames();
    ASSERT_GE(f.size(), 8u) << s.result.output;
    int restarts = 0, refinements = 0;
    for (std::size_t i = 1; i < f.size(); ++i) {
        const bool moved = f[i]["camera"] != f[i - 1]["camera"];
        const auto spp = f[i]["spp"].get<std::uint64_t>(), added = f[i]["added_spp"].get<std::uint64_t>();
        ASSERT_GE(added, 1u) << "frame " << i << " added no samples";
        if (moved) {
            // The mean restarted: all its samples are this frame's.
            EXPECT_EQ(spp, added) << "frame " << i << ": the camera moved but the mean kept older samples";
            ++restarts;
        } else {
            EXPECT_EQ(spp, f[i - 1]["spp"].get<std::uint64_t>() + added) << "frame " << i << " did not refine";
            ++refinements;
        }
    }
    EXPECT_EQ(restarts, 3) << "two frames of W and one drag";
    EXPECT_GE(refinements, 5);
    // W moved the eye forward (+z in the Cornell box), the drag turned the view.
    const auto& first = f.front()["camera"], & last = f.back()["camera"];
    EXPECT_GT(last["eye"][2].get<double>(), first["eye"][2].get<double>());
    EXPECT_NE(last["target"], first["target"]);
    // The printed camera is the scene-file snippet of the camera in use.
    const auto snippet_at = s.result.output.find("{\"camera\": ");
    ASSERT_NE(snippet_at, std::string::npos) << s.result.output;
    const json snippet = json::parse(s.result.output.substr(snippet_at, s.result.output.find('\n', snippet_at) - snippet_at));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(snippet["camera"]["eye"][i].get<float>(), last["eye"][i].get<float>());
    EXPECT_EQ(snippet["camera"]["resolution"], json::array({kWidth, kHeight}));
}

// A click focuses the thin lens on the surface under the cursor: the near
// ball, then the ball at the target; a click on the sky changes nothing.
TEST(Session, ClickFocusesTheLensThere) {
    const std::string dir = test_dir();
    fs::path root = fs::current_path();
    while (!root.empty() && !fs::exists(root / "benchmarks/references/scenes/thin-lens.json") && root != root.parent_path())
        root = root.parent_path();
    const std::string scene = (root / "benchmarks/references/scenes/thin-lens.json").string();
    ASSERT_TRUE(fs::exists(scene)) << scene;
    // Window pixels of a 64x48 view: the near (red) ball is right of centre
    // and low (image right is world -x), the focused ball at the centre, the
    // sky along the top left.
    const Session s = view(dir,
                           "wait-spp 2\n"
                           "click 50 32\n"
                           "wait 2\n"
                           "click 32 24\n"
                           "wait 2\n"
                           "click 16 1\n"
                           "wait 2\n"
                           "camera\n"
                           "quit\n",
                           scene);
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    std::vector<json> focus;
    for (const auto& l : s.log)
        if (l.value("event", "") == "focus") focus.push_back(l);
    ASSERT_EQ(focus.size(), 3u) << s.result.output;
    // Distances along the view: the red ball's centre 2.23 (radius 0.35), the
    // green one's 4.02 (radius 0.4).
    const double near_ball = focus[0]["focus_distance"].get<double>();
    const double target_ball = focus[1]["focus_distance"].get<double>();
    EXPECT_GT(near_ball, 2.23 - 0.36);
    EXPECT_LT(near_ball, 2.23);
    EXPECT_GT(target_ball, 4.02 - 0.41);
    EXPECT_LT(target_ball, 4.02);
    EXPECT_TRUE(focus[2]["focus_distance"].is_null()) << "the sky has no surface";
    // Each focus restarted the mean and the frames after it carry the distance.
    const auto f = s.frames();
    const double scene_focus = f.front()["camera"]["focus_distance"].get<double>();
    EXPECT_DOUBLE_EQ(scene_focus, 4.0);
    EXPECT_FLOAT_EQ(f.back()["camera"]["focus_distance"].get<float>(), float(target_ball));
    int restarts = 0;
    for (std::size_t i = 1; i < f.size(); ++i)
        if (f[i]["camera"] != f[i - 1]["camera"]) {
            ++restarts;
            EXPECT_EQ(f[i]["spp"], f[i]["added_spp"]) << "frame " << i << ": the focus changed but the mean kept older samples";
        }
    EXPECT_EQ(restarts, 2);
    // The printed snippet carries the lens, so a render sees what the window showed.
    const auto at = s.result.output.find("{\"camera\": ");
    ASSERT_NE(at, std::string::npos) << s.result.output;
    const json snippet = json::parse(s.result.output.substr(at, s.result.output.find('\n', at) - at));
    EXPECT_FLOAT_EQ(snippet["camera"]["aperture_radius"].get<float>(), 0.12f);
    EXPECT_FLOAT_EQ(snippet["camera"]["focus_distance"].get<float>(), float(target_ball));
}

TEST(Session, KeysSwitchTheViewAndExposure) {
    const std::string dir = test_dir();
    const Session s = view(dir,
                           "wait-spp 4\nscreenshot path-a\n"
                           "key 4\nwait 1\nwait-spp 4\nscreenshot normals\n"
                           "key 1\nwait 1\nwait-spp 4\nscreenshot path-b\n"
                           "key =\nkey =\nscreenshot path-brighter\n"
                           "quit\n",
                           "--max-spp 4");
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    // The state log follows the keys: path, then normals, then path again, each a restart.
    std::vector<std::string> views;
    for (const auto& f : s.frames()) {
        const std::string v = f["integrator"];
        if (views.empty() || views.back() != v) {
            views.push_back(v);
            EXPECT_EQ(f["spp"], f["added_spp"]) << "switching to " << v << " did not restart the mean";
        }
        EXPECT_EQ(f["error"], "") << "the " << v << " view failed";
    }
    EXPECT_EQ(views, (std::vector<std::string>{"path", "normals", "path"}));
    const float exposure = s.frames().back()["exposure"];
    EXPECT_NEAR(exposure, 2.0f, 1e-6f) << "two half stops up";

    const Image a = read_image(dir + "/path-a.exr"), n = read_image(dir + "/normals.exr"),
                b = read_image(dir + "/path-b.exr"), bright = read_image(dir + "/path-brighter.exr");
    // The renderer is deterministic per seed and sample: the same view at the
    // same spp is the same image, and another view is another image.
    EXPECT_EQ(differing_pixels(a, b), 0u) << "path view not restored";
    EXPECT_GT(differing_pixels(a, n), std::size_t(kWidth * kHeight / 2)) << "key 4 did not change the image";
    // Exposure scales what is shown (the PNG), not the saved mean (the EXR).
    EXPECT_EQ(differing_pixels(b, bright), 0u);
    // The PNGs are the EXR's mean times the exposure, sRGB-encoded to 8 bits.
    for (const auto& [png_file, scale] : {std::pair{"/path-b.png", 1.0f}, std::pair{"/path-brighter.png", exposure}}) {
        const Image png = read_image(dir + png_file);
        ASSERT_EQ(png.rgb.size(), b.rgb.size());
        int worst = 0;
        for (std::size_t i = 0; i < png.rgb.size(); ++i) {
            const int expect = int(std::lround(255 * srgb_encode(scale * b.rgb[i])));
            worst = std::max(worst, std::abs(int(std::lround(255 * srgb_encode(png.rgb[i]))) - expect));
        }
        EXPECT_LE(worst, 1) << png_file << ": 8-bit values differ from the exposed mean by more than rounding";
    }
}

TEST(Session, BvhOverlayAndHudShowInTheWindow) {
    const std::string dir = test_dir();
    const Session s = view(dir,
                           "wait-spp 2\nwait 1\ncapture " + dir + "/plain.png\n"
                           "key b\nwait 1\ncapture " + dir + "/boxes.png\n"
                           "key ]\nkey ]\nwait 1\ncapture " + dir + "/deeper.png\n"
                           "key b\nwait 1\ncapture " + dir + "/plain-again.png\n"
                           "key h\nwait 1\ncapture " + dir + "/hud.png\n"
                           "quit\n",
                           "--max-spp 2 --hide-hud");
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    const Image plain = read_image(dir + "/plain.png"), boxes = read_image(dir + "/boxes.png"),
                deeper = read_image(dir + "/deeper.png"), again = read_image(dir + "/plain-again.png"),
                hud = read_image(dir + "/hud.png");
    ASSERT_EQ(plain.width, kWidth);
    ASSERT_EQ(plain.height, kHeight);
    // With the image converged (--max-spp) the window changes only with the overlay.
    EXPECT_EQ(differing_pixels(plain, again), 0u) << "the overlay left something behind";
    const std::size_t box_pixels = differing_pixels(plain, boxes), deeper_pixels = differing_pixels(plain, deeper);
    EXPECT_GT(box_pixels, 0u) << "key B drew no boxes";
    EXPECT_GT(deeper_pixels, box_pixels) << "deeper levels add boxes";
    EXPECT_GT(differing_pixels(plain, hud), 0u) << "key H showed no heads-up display";
    std::vector<int> depths;
    for (const auto& f : s.frames())
        if (depths.empty() || depths.back() != f["bvh_depth"].get<int>()) depths.push_back(f["bvh_depth"]);
    EXPECT_EQ(depths, (std::vector<int>{0, 3, 5, 0}));
}

TEST(Session, ScreenshotAgreesWithRenderOfTheSameCamera) {
    const std::string dir = test_dir();
    constexpr unsigned kViewSpp = 32, kRefSpp = 8, kRefs = 16;
    // Fly away and come back (R): the screenshot is of the scene's camera.
    const Session s = view(dir,
                           "wait-spp 2\nhold w 2\ndrag 15 5\nwait 1\nkey r\nwait 1\n"
                           "wait-spp " + std::to_string(kViewSpp) + "\nscreenshot\nquit\n",
                           "--max-spp " + std::to_string(kViewSpp));
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    const Image view_image = read_image(dir + "/cornell-" + std::to_string(kViewSpp) + "spp.exr");
    ASSERT_EQ(view_image.width, kWidth);

    // Independent renders: seeds 1..K, the viewer's is 0.
    std::vector<Image> refs;
    for (unsigned k = 1; k <= kRefs; ++k) {
        const std::string out = dir + "/ref-" + std::to_string(k) + ".pfm";
        const ProcessResult r = run_shell(std::string(CLPATH_EXE) + " render -q --spp " + std::to_string(kRefSpp) +
                                          " --seed " + std::to_string(k) + " --width " + std::to_string(kWidth) +
                                          " --height " + std::to_string(kHeight) + " -o " + out);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        refs.push_back(read_image(out));
    }
    const double alpha = 1e-4;
    const BlockAgreement agree = compare_blocks(view_image, kViewSpp, refs, kRefSpp, alpha);
    EXPECT_TRUE(agree.agrees) << agree.report;
    std::printf("viewer vs render: %s\n", agree.report.c_str());
    // The test can fail: the same image mirrored (red and green walls swapped) must not pass.
    const BlockAgreement wrong = compare_blocks(mirrored(view_image), kViewSpp, refs, kRefSpp, alpha);
    EXPECT_FALSE(wrong.agrees) << "a mirrored image passed: " << wrong.report;
    std::printf("mirrored vs render: %s\n", wrong.report.c_str());
}

// A resize makes a new film only (the scene stays on the device, the kernels
// stay built): the image after it is, bit for bit, the one a viewer opened at
// that size renders.
TEST(Session, ResizedViewRendersLikeOneOpenedAtThatSize) {
    const std::string dir = test_dir();
    // The new size is followed once it has held 0.2 s; at --max-spp a frame
    // sleeps half a frame budget, so 200 frames are far longer than that.
    const Session resized = view(dir, "wait-spp 2\nresize 80 60\nwait 200\nwait-spp 8\nscreenshot resized\nquit\n",
                                 "--max-spp 8");
    ASSERT_EQ(resized.result.exit_code, 0) << resized.result.output;
    const auto frames = resized.frames();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames.front()["width"], kWidth);
    EXPECT_EQ(frames.back()["width"], 80);
    EXPECT_EQ(frames.back()["height"], 60);
    fs::create_directories(dir + "/opened");
    const Session opened = view(dir + "/opened", "wait-spp 8\nscreenshot opened\nquit\n", "--max-spp 8", 80, 60);
    ASSERT_EQ(opened.result.exit_code, 0) << opened.result.output;
    const Image a = read_image(dir + "/resized.exr"), b = read_image(dir + "/opened/opened.exr");
    ASSERT_EQ(a.width, 80);
    ASSERT_EQ(a.height, 60);
    ASSERT_EQ(b.width, 80);
    EXPECT_EQ(differing_pixels(a, b), 0u);
    EXPECT_GT(differing_pixels(a, mirrored(a)), 0u) << "the comparison would not see a wrong image";
}

TEST(Session, CtrlCExitsCleanly) {
    const std::string dir = test_dir();
    const std::string log = dir + "/state.jsonl";
    // The viewer runs in the background under Xvfb; once it has drawn a frame, SIGINT.
    // The first frame waits for the kernels' compile (a cold cache on a busy
    // machine: a minute or more), so the wait is bounded by minutes, not seconds.
    const std::string inner = std::string(CLPATH_EXE) + " view --width 64 --height 48 --state-log " + log +
                              " --screenshot-dir " + dir + " & pid=$!; i=0; while [ ! -s " + log +
                              " ] && [ $i -lt 3000 ]; do sleep 0.1; i=$((i+1)); done; sleep 0.5; kill -INT $pid; "
                              "wait $pid; echo exit=$?";
    const ProcessResult r = run_shell(xvfb_run() + " sh -c '" + inner + "'");
    EXPECT_NE(r.output.find("exit=0"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(interrupted)"), std::string::npos) << r.output;
}

namespace {

// Pixel-to-pixel variation as displayed: the mean squared difference of
// horizontally and vertically adjacent pixels' sRGB values (clamped, as the
// window shows them: in linear radiance the lamp's edges, 30 times brighter
// than the walls, would outweigh all the noise). Monte Carlo noise is
// independent from pixel to pixel and adds to it; a denoiser removes it.
double neighbour_energy(const Image& img) {
    const auto v = [&](int x, int y, int c) { return double(srgb_encode(img.at(x, y, c))); };
    double sum = 0;
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                if (x + 1 < img.width) sum += std::pow(v(x + 1, y, c) - v(x, y, c), 2), ++n;
                if (y + 1 < img.height) sum += std::pow(v(x, y + 1, c) - v(x, y, c), 2), ++n;
            }
    return sum / double(n);
}

double channel_mean(const Image& img, int c) {
    double sum = 0;
    for (std::size_t i = c; i < img.rgb.size(); i += 3) sum += img.rgb[i];
    return sum / double(img.rgb.size() / 3);
}

int max_byte_difference(const Image& a, const Image& b) {
    if (a.rgb.size() != b.rgb.size()) return 256;
    int worst = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        worst = std::max(worst, std::abs(int(std::lround(255 * srgb_encode(a.rgb[i]))) -
                                         int(std::lround(255 * srgb_encode(b.rgb[i])))));
    return worst;
}

// What a denoised image must be of its estimate: much smoother (under a
// quarter of its pixel-to-pixel variation: at 16 spp that is almost all
// noise, which OIDN removes nearly whole; the estimate itself, or another
// noisy estimate, scores about 1) and as bright (each channel's mean within
// 10%: a denoiser moves energy between neighbours, it does not make or lose
// it, beyond what clamping fireflies takes). Empty: it is.
std::string denoised_problems(const Image& denoised, const Image& estimate) {
    std::string p;
    const double ratio = neighbour_energy(denoised) / neighbour_energy(estimate);
    if (!(ratio < 0.25)) p += "pixel-to-pixel variation " + std::to_string(ratio) + " of the estimate's; ";
    for (int c = 0; c < 3; ++c) {
        const double m = channel_mean(denoised, c), e = channel_mean(estimate, c);
        if (!(std::abs(m - e) <= 0.1 * e)) p += "channel " + std::to_string(c) + " mean " + std::to_string(m) +
                                               ", the estimate's " + std::to_string(e) + "; ";
    }
    return p;
}

}  // namespace

// Key N shows the estimate denoised: the window shows the denoised image
// (checked against the screenshot's .denoised twin), the estimate keeps
// accumulating and is the bits a viewer without the key renders, key N again
// shows the estimate, and a camera move shows the raw estimate until the new
// view's guides and first denoise are done.
TEST(Session, DenoiseKeyShowsTheEstimateDenoisedAndLeavesItUnchanged) {
    const std::string dir = test_dir();
    constexpr int kSpp = 4;
    const std::string spp = std::to_string(kSpp);
    const Session s = view(dir,
                           "key n\nwait-spp " + spp + "\nwait-denoised\n"
                           "capture " + dir + "/den-window.png\nscreenshot den\n"
                           "key n\nwait 1\ncapture " + dir + "/raw-window.png\nscreenshot raw\n"
                           "key n\ndrag 6 0\nwait 2\nwait-spp " + spp + "\nwait-denoised\nquit\n",
                           "--hide-hud --max-spp " + spp);
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    const auto frames = s.frames();
    ASSERT_FALSE(frames.empty());
    if (frames.back()["denoise"]["state"] == "unavailable")
        GTEST_SKIP() << "SKIPPED: Open Image Denoise is not installed, nothing tested: "
                     << frames.back()["denoise"]["message"].get<std::string>();

    // The estimate with the key pressed is the one without it, bit for bit.
    fs::create_directories(dir + "/plain");
    const Session plain = view(dir + "/plain", "wait-spp " + spp + "\nscreenshot plain\nquit\n", "--hide-hud --max-spp " + spp);
    ASSERT_EQ(plain.result.exit_code, 0) << plain.result.output;
    const Image estimate = read_image(dir + "/plain/plain.exr"), den_estimate = read_image(dir + "/den.exr"),
                raw_estimate = read_image(dir + "/raw.exr"), denoised = read_image(dir + "/den.denoised.exr");
    EXPECT_EQ(differing_pixels(estimate, den_estimate), 0u) << "denoising changed the estimate";
    EXPECT_EQ(differing_pixels(estimate, raw_estimate), 0u);
    EXPECT_FALSE(fs::exists(dir + "/raw.denoised.exr")) << "a screenshot with denoising off wrote a denoised twin";
    ASSERT_EQ(denoised.width, kWidth);
    ASSERT_EQ(denoised.height, kHeight);

    // Denoised in the expected way, by a criterion that rejects the estimate
    // itself and another noisy estimate (seed 1) as "denoised".
    const std::string problems = denoised_problems(denoised, estimate);
    EXPECT_EQ(problems, "");
    std::printf("pixel-to-pixel variation, denoised / estimate at %d spp: %.4f\n", kSpp,
                neighbour_energy(denoised) / neighbour_energy(estimate));
    EXPECT_NE(denoised_problems(estimate, estimate), "");
    const std::string other = dir + "/other-seed.pfm";
    const ProcessResult r = run_shell(std::string(CLPATH_EXE) + " render -q --spp " + spp + " --seed 1 --width " +
                                      std::to_string(kWidth) + " --height " + std::to_string(kHeight) + " -o " + other);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(denoised_problems(read_image(other), estimate), "") << "another noisy estimate passed as denoised";

    // The window showed the denoised image, then (key N again) the estimate.
    EXPECT_LE(max_byte_difference(read_image(dir + "/den-window.png"), read_image(dir + "/den.denoised.png")), 1);
    EXPECT_LE(max_byte_difference(read_image(dir + "/raw-window.png"), read_image(dir + "/raw.png")), 1);
    EXPECT_GT(differing_pixels(read_image(dir + "/den-window.png"), read_image(dir + "/raw-window.png")), 0u);

    // The log: while on, the estimate went on growing, and the shown image
    // was denoised at a bounded rate (DenoisePacing: 1.25x the samples
    // between two, plus the first and the last), never from the future.
    std::vector<std::uint64_t> shown;
    std::uint64_t spp_when_on = 0;
    bool on = false, moved = false, raw_after_move = false;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const json& d = frames[i]["denoise"];
        const auto spp_now = frames[i]["spp"].get<std::uint64_t>();
        if (i > 0 && frames[i]["camera"] != frames[i - 1]["camera"]) {
            moved = true;
            raw_after_move = d["shown_spp"].is_null();
        }
        if (d["state"] != "on") {
            if (on) EXPECT_TRUE(d["shown_spp"].is_null());
            continue;
        }
        if (!on) spp_when_on = spp_now;
        on = true;
        if (d["shown_spp"].is_null()) continue;
        const auto n = d["shown_spp"].get<std::uint64_t>();
        EXPECT_LE(n, spp_now);
        EXPECT_GT(d["ms"].get<double>(), 0.0);
        if (!moved && (shown.empty() || shown.back() != n)) shown.push_back(n);
    }
    // The key was pressed before the first sample; the first frame adds one.
    EXPECT_EQ(spp_when_on, 1u) << "the estimate did not go on growing with denoising on";
    ASSERT_FALSE(shown.empty());
    EXPECT_EQ(shown.back(), std::uint64_t(kSpp));
    EXPECT_LE(shown.size(), 2 + std::ceil(std::log(double(kSpp)) / std::log(1.25)));
    EXPECT_TRUE(moved);
    EXPECT_TRUE(raw_after_move) << "the frame after the move showed the old view's denoised image";
    EXPECT_EQ(frames.back()["denoise"]["shown_spp"], kSpp) << "the moved view was not denoised";
}

// Without the library the key leaves the estimate on screen and says why in
// the heads-up display (orange text that was not there before) and the
// terminal; nothing crashes, hangs or writes a denoised file.
TEST(Session, DenoiseKeyWithoutTheLibrarySaysWhyAndGoesOn) {
    const std::string dir = test_dir();
    ::setenv("CLPATH_OIDN_LIBRARY", (dir + "/no-such-oidn.so").c_str(), 1);
    const Session s = view(dir,
                           "wait-spp 4\ncapture " + dir + "/before.png\nkey n\nwait 1\nwait-denoised\n"
                           "capture " + dir + "/after.png\nscreenshot shot\nkey n\nwait 1\nquit\n",
                           "--max-spp 4", 320, 240);
    ::unsetenv("CLPATH_OIDN_LIBRARY");
    ASSERT_EQ(s.result.exit_code, 0) << s.result.output;
    EXPECT_NE(s.result.output.find("cannot denoise: denoising needs Intel Open Image Denoise 2, and "
                                   "CLPATH_OIDN_LIBRARY=" + dir + "/no-such-oidn.so does not load it"),
              std::string::npos)
        << s.result.output;
    const auto frames = s.frames();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames.front()["denoise"]["state"], "off");
    const json& last = frames.back()["denoise"];
    EXPECT_EQ(last["state"], "unavailable");
    EXPECT_EQ(last["message"].get<std::string>().rfind("denoising needs Intel Open Image Denoise 2", 0), 0u) << last;
    for (const auto& f : frames) EXPECT_TRUE(f["denoise"]["shown_spp"].is_null());
    EXPECT_TRUE(fs::exists(dir + "/shot.exr"));
    EXPECT_FALSE(fs::exists(dir + "/shot.denoised.exr"));
    // The message's colour (hud.cpp: 1, 0.75, 0.3) over the panel.
    const auto orange_pixels = [](const Image& img) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
            const float r = srgb_encode(img.rgb[i]), g = srgb_encode(img.rgb[i + 1]), b = srgb_encode(img.rgb[i + 2]);
            n += r > 0.6f && g > 0.55f * r && g < 0.9f * r && b < 0.55f * g;
        }
        return n;
    };
    const std::size_t before = orange_pixels(read_image(dir + "/before.png")),
                      after = orange_pixels(read_image(dir + "/after.png"));
    std::printf("orange pixels: %zu before the key, %zu after\n", before, after);
    EXPECT_GT(after, before + 100) << "the heads-up display shows no message";
}
