// Any scene, rendered the hard way (robustness suite, general part): every
// scene file in a folder is rendered small and must load without error,
// render with zero non-finite samples, and agree in distribution with itself
// moved far from the origin and scaled by 1e-4 and 1e4 (test::placed: the
// image is invariant in exact arithmetic; float differences are what is tested).
//
// The folder: $CLPATH_HARD_SCENES (every *.json in it), else scenes/hard/ and
// the bundled scenes/ of this repository. A scene that is not in the
// repository is tested by pointing the variable at its folder:
//   CLPATH_HARD_SCENES=/path/to/scenes ctest --test-dir build -R HardScenes
//
// The move: by 10^3 times the scene's size (as the 1e3 case of scale_test), but
// never so far that the float spacing there exceeds 1e-3 of the scene's
// shortest edge (a room moved to 1e6 loses its 1e-5 gaps to rounding: that is
// a different scene, not a robustness failure); a scene whose detail allows
// no move of at least 10 times its size is only scaled, and the test says so.
// A scene far from the origin (scenes/hard/far-from-origin.json) is also
// compared with itself moved to the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "scene/load/scene_loader.hpp"
#include "support/image_agreement.hpp"
#include "support/render_runs.hpp"

using namespace clpath;
namespace fs = std::filesystem;

namespace {

// The repository's scenes/: found by walking up from the working directory
// (ctest runs tests in build/tests).
fs::path repo_scenes() {
    for (fs::path p = fs::current_path(); !p.empty(); p = p.parent_path()) {
        if (fs::is_directory(p / "scenes" / "hard")) return p / "scenes";
        if (p == p.parent_path()) break;
    }
    return {};
}

std::vector<fs::path> scene_files() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("CLPATH_HARD_SCENES"); env && *env) {
        dirs.push_back(env);
    } else if (const fs::path s = repo_scenes(); !s.empty()) {
        dirs = {s / "hard", s};
    }
    std::vector<fs::path> files;
    for (const auto& d : dirs) {
        std::vector<fs::path> here;
        for (const auto& e : fs::directory_iterator(d))
            if (e.is_regular_file() && e.path().extension() == ".json") here.push_back(e.path());
        std::sort(here.begin(), here.end());
        files.insert(files.end(), here.begin(), here.end());
    }
    return files;
}

struct Extent {
    glm::dvec3 lo{INFINITY}, hi{-INFINITY};
    double shortest_edge = INFINITY;
};

Extent extent(const Scene& s) {
    Extent e;
    for (const auto& v : s.vertices) {
        e.lo = glm::min(e.lo, glm::dvec3(v));
        e.hi = glm::max(e.hi, glm::dvec3(v));
    }
    for (std::size_t i = 0; i < s.vertices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            const double l = glm::length(glm::dvec3(s.vertices[i + k]) - glm::dvec3(s.vertices[i + (k + 1) % 3]));
            if (l > 0) e.shortest_edge = std::min(e.shortest_edge, l);
        }
    return e;
}

void check_scene(const fs::path& file) {
    SCOPED_TRACE(file.string());
    Scene s;
    ASSERT_NO_THROW(s = load_scene(file.string())) << "the scene does not load";
    const int w = s.camera.width, h = s.camera.height;
    s.camera.width = 32;
    s.camera.height = std::clamp(int(std::lround(32.0 * h / w)), 8, 64);
    RenderSettings st = settings_from_scene(s.render);
    st.max_depth = std::min<std::uint32_t>(st.max_depth, 8);
    std::uint64_t nonfinite = 0;
    const std::uint32_t spp = 8;
    const int k = 8;
    const auto original = test::render_runs(s, st, spp, k, 1000, &nonfinite);
    EXPECT_EQ(nonfinite, 0u) << "non-finite samples in the original";
    const auto ref = test::reference_from_runs("original", original);

    // Of the geometry placed: an instanced mesh's copies count with their own details.
    const Extent e = extent(s.instances.empty() ? s : flatten_instances(s));
    const double size = glm::length(e.hi - e.lo);
    const double far = std::max({std::fabs(e.lo.x), std::fabs(e.lo.y), std::fabs(e.lo.z), std::fabs(e.hi.x),
                                 std::fabs(e.hi.y), std::fabs(e.hi.z)});
    // Largest power of ten up to 1000 sizes with ulp(|x| + move) <= 1e-3 shortest edge.
    double move = std::pow(10.0, std::floor(std::log10(1000 * size)));
    while (move > 0 && (far + move) * 0x1.0p-23 > 1e-3 * e.shortest_edge) move /= 10;
    std::vector<std::pair<std::string, Scene>> versions = {{"scaled by 1e-4", test::placed(s, 1e-4, glm::dvec3(0))},
                                                           {"scaled by 1e4", test::placed(s, 1e4, glm::dvec3(0))}};
    // A scene already far out is also brought home (always allowed: rounding only shrinks).
    const glm::dvec3 centre = 0.5 * (e.lo + e.hi);
    if (glm::length(centre) > 10 * size)
        versions.push_back({"moved to the origin", test::placed(s, 1, -glm::round(centre))});
    if (move >= 10 * size)
        versions.push_back({"moved by " + std::to_string(move), test::placed(s, 1, glm::dvec3(move))});
    else
        std::fprintf(stderr, "[ note    ] %s: detail of %g in a scene of size %g: not moved\n", file.filename().c_str(),
                     e.shortest_edge, size);
    std::uint32_t seed = 2000;
    for (const auto& [what, v] : versions) {
        std::uint64_t nf = 0;
        const auto runs = test::render_runs(v, st, spp, k, seed += 100, &nf);
        EXPECT_EQ(nf, 0u) << what << ": non-finite samples";
        const auto r = test::pixel_agreement(runs, ref);
        EXPECT_TRUE(r.ok()) << what << ": " << r.describe();
        std::fprintf(stderr, "[ scene   ] %s %s: %.2f%% of pixel values agree\n", file.filename().c_str(),
                     what.c_str(), 100 * r.pass_fraction());
    }
}

}  // namespace

TEST(HardScenes, EverySceneRendersFiniteAndScaleInvariant) {
    const auto files = scene_files();
    ASSERT_FALSE(files.empty()) << "no scene files found (CLPATH_HARD_SCENES or the repository's scenes/)";
    for (const auto& f : files) check_scene(f);
}
