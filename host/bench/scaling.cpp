#include "bench/scaling.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "bench/embree_baseline.hpp"
#include "bench/ray_batches.hpp"
#include "bench/report_files.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scenes.hpp"
#include "util/error.hpp"
#include "util/median.hpp"

namespace clpath {
namespace {

// Timed passes of the path column, after its warm-up; the median is reported.
constexpr int kPathPasses = 3;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double mem_available_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    double kb = 0;
    std::string unit;
    while (in >> key >> kb >> unit)
        if (key == "MemAvailable:") return kb * 1024;
    return 0;
}

std::string gib(double bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / double(1ull << 30));
    return buf;
}

// Measures one structure on one scene; throws clpath::Error (e.g. too large for the device).
void measure(Context& ctx, const Scene& scene, Accel accel, const ScalingOptions& o, ScalingRow& row) {
    RayBenchOptions ro;
    ro.width = o.ray_width;
    ro.height = o.ray_height;
    ro.launches = o.launches;
    ro.accel = accel;
    ro.check = o.check;
    // Embree's default mode, as its users run it, beside the BVH (the flat
    // structure is a model of the thesis renderer, not a peer of Embree's);
    // robust mode would double the Embree builds at 10^7 triangles for a
    // ratio `bench rays` reports already.
    ro.embree = o.embree && accel == Accel::Bvh;
    ro.embree_robust = false;
    const RayBenchResult r = run_ray_bench(ctx, scene, ro);
    row.build_ms = r.structure.build_ms;
    row.mtris_per_s = r.structure.build_ms > 0 ? double(row.triangles) / (r.structure.build_ms * 1e-3) * 1e-6 : 0;
    row.sah_cost = r.structure.sah_cost;
    row.nodes = r.structure.node_count;
    row.bytes_per_triangle = double(r.structure_bytes) / double(row.triangles);
    // Each batch's rate from its median launch, and the path column's from
    // the median of three passes: a launch slowed by another process taking
    // a core for a moment moved a mean of three launches by up to a fifth
    // (scaling:300 diffuse 15.98 against 19.07-19.73 Mrays/s, EPYC, idle),
    // while fresh processes' best launches agreed within 1.1 %
    // (benchmarks/scaling/process_spread.sh).
    auto median_rate = [](const BatchResult& b) {
        return b.median_ms > 0 ? double(b.rays) / (b.median_ms * 1e-3) * 1e-6 : 0;
    };
    row.primary_mrays = median_rate(r.batches[0]);
    row.shadow_mrays = median_rate(r.batches[1]);
    row.diffuse_mrays = median_rate(r.batches[2]);
    auto embree_rate = [](const BatchResult& b) {
        const EmbreeBatch& e = b.embree_in(EmbreeMode::Default);
        return e.ran && e.median_ms > 0 ? double(b.rays) / (e.median_ms * 1e-3) * 1e-6 : 0;
    };
    row.embree_primary_mrays = embree_rate(r.batches[0]);
    row.embree_shadow_mrays = embree_rate(r.batches[1]);
    row.embree_diffuse_mrays = embree_rate(r.batches[2]);
    for (const auto& b : r.batches) {
        row.checked += b.agreement.checked;
        row.mismatched += b.agreement.mismatched;
    }
    // Embree's answers are checked against the CPU reference like the
    // device's, but counted apart: its default mode may miss a ray that
    // grazes an edge (not watertight), which says nothing about clpath.
    for (const auto& b : r.batches) row.embree_mismatched += b.embree_in(EmbreeMode::Default).agreement.mismatched;
    Scene small = scene;
    small.camera.width = o.path_width;
    small.camera.height = o.path_height;
    RenderSettings settings = settings_from_scene(small.render);
    settings.accel = accel;
    Renderer renderer(ctx, small, settings);
    // Warm-up with the timed pass's own sample count: a device may finish
    // compiling at the first launch of each launch shape, and one sample per
    // pixel launches other shapes than several (IntegratorProgram::add_samples
    // sizes its launches by the speed it measured): warmed with one, the first
    // run's smallest scene timed PoCL's compile (CV 65 % between runs, EPYC).
    renderer.add_samples(o.path_spp);
    std::vector<double> samples_per_s, rays_per_s;
    for (int pass = 0; pass < kPathPasses; ++pass) {
        renderer.reset();
        renderer.add_samples(o.path_spp);
        const RenderStats& st = renderer.stats();
        const double samples = double(st.samples_per_pixel) * o.path_width * o.path_height;
        samples_per_s.push_back(st.render_seconds > 0 ? samples / st.render_seconds * 1e-6 : 0);
        // Every ray the megakernel traced (camera, bounce and shadow), so its rate
        // sits beside the diffuse batch's: the gap between them is the cost of shading.
        rays_per_s.push_back(st.render_seconds > 0 ? double(st.rays) / st.render_seconds * 1e-6 : 0);
    }
    row.msamples_per_s = median_of(samples_per_s);
    row.path_mrays_per_s = median_of(rays_per_s);
}

}  // namespace

std::vector<std::size_t> scaling_sizes(std::size_t min, std::size_t max) {
    std::vector<std::size_t> sizes;
    if (min > max) return sizes;
    sizes.push_back(min);
    for (std::size_t decade = 1; decade <= max; decade *= 10)
        for (std::size_t step : {1, 3}) {
            const std::size_t n = decade * step;
            if (n > min && n <= max) sizes.push_back(n);
        }
    if (sizes.back() != max) sizes.push_back(max);
    return sizes;
}

double scaling_memory_estimate(std::size_t triangles, bool embree) {
    // Per triangle, at the peak: the scene (36 B vertices + 8 B ids), the
    // builder's boxes, centroids and indices (40 B) and binary nodes (~40 B),
    // two structures (the measured one and the CPU reference, ~85 B each, the
    // renderer's again) and their device copies, which on a CPU device are
    // host memory (~85 B each). Rounded up to 600 B: an estimate from the
    // structures' sizes, deliberately generous, not a measured peak. Embree's
    // scene adds about 140 B (peak resident 1.80 GB against 1.39 GB without it
    // at 2,999,836 triangles), counted as 200.
    return (embree ? 800.0 : 600.0) * double(triangles) + 256.0 * (1 << 20);
}

std::vector<ScalingRow> run_scaling(Context& ctx, const ScalingOptions& o,
                                    const std::function<void(const std::string&)>& log) {
    auto say = [&](const std::string& s) {
        if (log) log(s);
    };
    if (o.min < 100 || o.max > 50'000'000 || o.min > o.max)
        throw Error("bench scaling: sizes must satisfy 100 <= min <= max <= 50000000, got min " +
                    std::to_string(o.min) + ", max " + std::to_string(o.max));
    const double budget = o.memory_budget_bytes > 0 ? o.memory_budget_bytes : 0.8 * mem_available_bytes();
    std::vector<ScalingRow> rows;
    bool flat_running = o.flat;
    std::string flat_stop;
    double flat_last_seconds = 0;
    std::size_t flat_last_size = 0;
    bool memory_stop = false;
    for (std::size_t n : scaling_sizes(o.min, o.max)) {
        ScalingRow base;
        base.requested = n;
        base.triangles = n;
        const double need = scaling_memory_estimate(n, o.embree && o.bvh && embree_built_in());
        if (memory_stop || (budget > 0 && need > budget)) {
            memory_stop = true;
            base.skipped = "needs about " + gib(need) + " of memory, more than the " + gib(budget) +
                           " available to the benchmark";
            for (Accel a : {Accel::Bvh, Accel::Flat}) {
                if ((a == Accel::Bvh && !o.bvh) || (a == Accel::Flat && !o.flat)) continue;
                ScalingRow r = base;
                r.accel = a;
                rows.push_back(r);
                say(std::to_string(n) + " " + accel_name(a) + ": skipped: " + r.skipped);
            }
            continue;
        }
        const auto g0 = std::chrono::steady_clock::now();
        Scene scene = scaling_scene(n);
        base.generate_ms = seconds_since(g0) * 1e3;
        base.triangles = scene.triangle_count();
        for (Accel a : {Accel::Bvh, Accel::Flat}) {
            if ((a == Accel::Bvh && !o.bvh) || (a == Accel::Flat && !o.flat)) continue;
            ScalingRow row = base;
            row.accel = a;
            if (a == Accel::Flat && flat_running && flat_last_size > 0) {
                // Flat traversal is linear in the triangles an object holds.
                const double predicted = flat_last_seconds * double(n) / double(flat_last_size);
                if (predicted > o.time_cap_s) {
                    flat_running = false;
                    char buf[160];
                    std::snprintf(buf, sizeof buf, "predicted %.0f s (from %zu triangles), over the %.0f s time cap",
                                  predicted, flat_last_size, o.time_cap_s);
                    flat_stop = buf;
                }
            }
            if (a == Accel::Flat && !flat_running) {
                row.skipped = flat_stop;
                rows.push_back(row);
                say(std::to_string(row.triangles) + " flat: skipped: " + row.skipped);
                continue;
            }
            const auto t0 = std::chrono::steady_clock::now();
            try {
                measure(ctx, scene, a, o, row);
            } catch (const Error& e) {
                row.skipped = e.what();
            }
            row.seconds = seconds_since(t0);
            if (a == Accel::Flat) {
                flat_last_seconds = row.seconds;
                flat_last_size = row.triangles;
                if (row.seconds > o.time_cap_s) {
                    flat_running = false;
                    flat_stop = "the previous size took longer than the time cap";
                }
            }
            char buf[480];
            if (row.skipped.empty())
                std::snprintf(buf, sizeof buf,
                              "%zu %s: generate %.0f ms, build %.1f ms (%.2f Mtris/s), SAH %.1f, %zu nodes, %.1f B/tri, "
                              "Mrays/s primary %.3f shadow %.3f diffuse %.3f (Embree %.3f %.3f %.3f), path %.4f Msamples/s %.3f "
                              "Mrays/s, CPU check %zu rays, %zu mismatched (%.1f s)",
                              row.triangles, accel_name(a), row.generate_ms, row.build_ms, row.mtris_per_s, row.sah_cost,
                              row.nodes, row.bytes_per_triangle, row.primary_mrays, row.shadow_mrays, row.diffuse_mrays,
                              row.embree_primary_mrays, row.embree_shadow_mrays, row.embree_diffuse_mrays,
                              row.msamples_per_s, row.path_mrays_per_s, row.checked, row.mismatched, row.seconds);
            else
                std::snprintf(buf, sizeof buf, "%zu %s: skipped: %s", row.triangles, accel_name(a), row.skipped.c_str());
            say(buf);
            rows.push_back(row);
        }
    }
    return rows;
}

std::string scaling_csv(const std::vector<ScalingRow>& rows, const std::string& device) {
    std::ostringstream s;
    s << "device,requested,triangles,accel,generate_ms,build_ms,build_mtris_per_s,sah_cost,nodes,bytes_per_triangle,"
         "primary_mrays_per_s,shadow_mrays_per_s,diffuse_mrays_per_s,path_msamples_per_s,path_mrays_per_s,"
         "checked_rays,mismatched,seconds,embree_primary_mrays_per_s,embree_shadow_mrays_per_s,"
         "embree_diffuse_mrays_per_s,embree_mismatched,skipped\n";
    for (const auto& r : rows) {
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      ",%zu,%zu,%s,%.3f,%.3f,%.4f,%.3f,%zu,%.2f,%.4f,%.4f,%.4f,%.5f,%.4f,%zu,%zu,%.2f,%.4f,%.4f,%.4f,%zu,",
                      r.requested, r.triangles, accel_name(r.accel), r.generate_ms, r.build_ms, r.mtris_per_s,
                      r.sah_cost, r.nodes, r.bytes_per_triangle, r.primary_mrays, r.shadow_mrays, r.diffuse_mrays,
                      r.msamples_per_s, r.path_mrays_per_s, r.checked, r.mismatched, r.seconds,
                      r.embree_primary_mrays, r.embree_shadow_mrays, r.embree_diffuse_mrays, r.embree_mismatched);
        s << csv_field(device) << buf << csv_field(r.skipped) << "\n";
    }
    return s.str();
}

std::string scaling_markdown(const std::vector<ScalingRow>& rows, const std::string& device) {
    std::ostringstream s;
    s << "Device: " << device << "\n\n"
      << "| triangles | structure | generate ms | build ms | build Mtris/s | SAH cost | nodes | bytes/tri | primary "
         "Mrays/s | shadow Mrays/s | diffuse Mrays/s | Embree primary | Embree shadow | Embree diffuse | path "
         "Msamples/s | path Mrays/s | CPU check |\n"
      << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& r : rows) {
        char buf[512];
        if (!r.skipped.empty()) {
            std::snprintf(buf, sizeof buf, "| %zu | %s | skipped: %s |||||||||||||||\n", r.triangles, accel_name(r.accel),
                          r.skipped.c_str());
        } else {
            auto rate = [](double v) {  // blank where Embree did not run
                char b[32] = "";
                if (v > 0) std::snprintf(b, sizeof b, "%.3f", v);
                return std::string(b);
            };
            std::snprintf(buf, sizeof buf,
                          "| %zu | %s | %.1f | %.2f | %.2f | %.2f | %zu | %.1f | %.3f | %.3f | %.3f | %s | %s | %s | %.4f | "
                          "%.3f | %s |\n",
                          r.triangles, accel_name(r.accel), r.generate_ms, r.build_ms, r.mtris_per_s, r.sah_cost,
                          r.nodes, r.bytes_per_triangle, r.primary_mrays, r.shadow_mrays, r.diffuse_mrays,
                          rate(r.embree_primary_mrays).c_str(), rate(r.embree_shadow_mrays).c_str(),
                          rate(r.embree_diffuse_mrays).c_str(), r.msamples_per_s, r.path_mrays_per_s,
                          r.mismatched ? (std::to_string(r.mismatched) + " of " + std::to_string(r.checked) +
                                          " rays MISMATCHED").c_str()
                                       : (std::to_string(r.checked) + " rays agree").c_str());
        }
        s << buf;
    }
    return s.str();
}

}  // namespace clpath
