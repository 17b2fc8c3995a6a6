#include "bench/path_bench.hpp"

#include <cstdio>
#include <iterator>
#include <memory>

#include "render/renderer.hpp"
#include "util/error.hpp"

namespace clpath {

double PathRound::samples_ratio(EmbreeMode m) const {
    const PathTiming& e = embree[int(m)];
    return e.msamples_per_s > 0 ? clpath.msamples_per_s / e.msamples_per_s : 0;
}
double PathRound::rays_ratio(EmbreeMode m) const {
    const PathTiming& e = embree[int(m)];
    return e.mrays_per_s > 0 ? clpath.mrays_per_s / e.mrays_per_s : 0;
}

namespace {

PathTiming timing(double seconds, std::uint64_t rays, std::uint64_t nonfinite, double samples) {
    PathTiming t;
    t.seconds = seconds;
    t.rays = rays;
    t.nonfinite = nonfinite;
    t.msamples_per_s = seconds > 0 ? samples / seconds * 1e-6 : 0;
    t.mrays_per_s = seconds > 0 ? double(rays) / seconds * 1e-6 : 0;
    return t;
}

}  // namespace

void check_path_bench_scene(const Scene& scene) {
    const auto why = embree_path_unsupported(scene);
    if (!why.empty()) {
        std::string all;
        for (const auto& w : why) all += (all.empty() ? "" : "; ") + w;
        throw UsageError("bench path supports diffuse surfaces lit by emissive triangles and point, spot or "
                         "directional lights only; unsupported here: " + all);
    }
    if (!embree_path_built_in())
        throw Error("bench path needs Embree, and this clpath was built without it (install libembree-dev and "
                    "configure again with -DCLPATH_WITH_EMBREE=ON)");
}

PathBenchResult run_path_bench(Context& ctx, const Scene& scene, const PathBenchOptions& o,
                               const std::function<void(const std::string&)>& log) {
    check_path_bench_scene(scene);
    if (o.rounds < 1) throw Error("bench path: rounds must be at least 1");
    if (o.spp < 2) throw Error("bench path: the agreement check needs at least 2 samples per pixel");

    PathBenchResult r;
    r.scene = scene.name;
    r.triangles = scene.triangle_count();
    r.width = scene.camera.width;
    r.height = scene.camera.height;
    r.spp = o.spp;
    r.max_depth = o.max_depth;
    r.clpath_device = ctx.device().describe();

    // What `clpath render --max-depth D --rr none` runs: the path integrator
    // (NEE + MIS), cosine-weighted bounces, the scene's BVH options.
    RenderSettings settings = settings_from_scene(scene.render);
    settings.integrator = CLP_INTEGRATOR_PATH;
    settings.max_depth = o.max_depth;
    settings.rr_rule = CLP_RR_NONE;
    settings.hemisphere = kHemisphereCosine;
    settings.seed = o.seed;
    if (log) log("compiling and uploading for " + r.clpath_device);
    const std::shared_ptr<const PreparedScene> prepared = prepare_scene(scene, settings);
    Renderer renderer(ctx, *prepared, settings);
    renderer.add_samples(1);  // warm-up: a device may finish compiling at the first launch
    std::vector<std::unique_ptr<EmbreePathTracer>> tracers;
    for (EmbreeMode mode : kEmbreeModes) {
        tracers.push_back(make_embree_path_tracer(scene, prepared, o.max_depth, mode, o.threads));
        r.embree[int(mode)] = tracers.back()->describe();
        tracers.back()->render(1, o.seed + 1);  // warm-up, as the device's
    }

    const double samples = double(o.spp) * r.width * r.height;
    Image clpath_image;
    PathSums embree_sums[2];
    for (int round = 0; round < o.rounds; ++round) {
        PathRound pr;
        renderer.reset();
        renderer.add_samples(o.spp);
        const RenderStats st = renderer.stats();
        pr.clpath = timing(st.render_seconds, st.rays, st.nonfinite, samples);
        if (round + 1 == o.rounds) clpath_image = renderer.resolve(1.0f).linear;
        std::string line;
        for (auto& tracer : tracers) {
            const int m = int(tracer->mode());
            EmbreePathRun er = tracer->render(o.spp, o.seed + 1);
            pr.embree[m] = timing(er.seconds, er.rays, er.nonfinite, samples);
            if (round + 1 == o.rounds) embree_sums[m] = std::move(er.sums);
            char buf[200];
            std::snprintf(buf, sizeof buf, "; Embree %s mode %.3f s, %.3f Msamples/s, %.3f Mrays/s, clpath/Embree %.3f",
                          embree_mode_name(tracer->mode()), pr.embree[m].seconds, pr.embree[m].msamples_per_s,
                          pr.embree[m].mrays_per_s, pr.rays_ratio(tracer->mode()));
            line += buf;
        }
        if (log) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "round %d: clpath %.3f s, %.3f Msamples/s, %.3f Mrays/s", round + 1,
                          pr.clpath.seconds, pr.clpath.msamples_per_s, pr.clpath.mrays_per_s);
            log(buf + line + " (Mrays/s)");
        }
        r.rounds.push_back(pr);
    }
    // Two checks per run: each at half the false-failure rate, so that a
    // correct run still fails with probability below 1e-6.
    for (EmbreeMode mode : kEmbreeModes)
        r.agreement[int(mode)] = check_path_agreement(clpath_image, o.spp, embree_sums[int(mode)], o.grid,
                                                      1e-6 / double(std::size(kEmbreeModes)));
    return r;
}

}  // namespace clpath
