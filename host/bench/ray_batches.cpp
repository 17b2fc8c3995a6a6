#include "bench/ray_batches.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <future>
#include <thread>

#include "bench/cpu_traversal.hpp"
#include "bench/embree_baseline.hpp"
#include "cl/embedded_sources.hpp"
#include "cl/program.hpp"
#include "render/kernel_programs.hpp"
#include "util/error.hpp"
#include "util/median.hpp"

namespace clpath {
namespace {

constexpr std::size_t kSamplesPerPixel = CLP_BATCH_SAMPLES;

// Indices of the rays checked: all, or `check` evenly spaced over the batch
// (so every part of the image is represented).
std::vector<std::size_t> checked_rays(std::size_t count, std::size_t check) {
    std::vector<std::size_t> idx;
    if (check == 0 || check >= count) {
        idx.resize(count);
        for (std::size_t i = 0; i < count; ++i) idx[i] = i;
        return idx;
    }
    idx.reserve(check);
    for (std::size_t i = 0; i < check; ++i) idx.push_back(i * count / check);
    return idx;
}

// f(i) for every i in [0, n), split over the hardware threads.
template <class F>
void parallel_for(std::size_t n, F f) {
    const std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::future<void>> jobs;
    for (std::size_t t = 0; t < threads; ++t)
        jobs.push_back(std::async(std::launch::async, [&, t] {
            for (std::size_t i = n * t / threads; i < n * (t + 1) / threads; ++i) f(i);
        }));
    for (auto& j : jobs) j.get();
}

std::string mismatch_report(std::size_t i, const BatchRay& r, std::int64_t dev_prim, double dev_t,
                            std::int64_t cpu_prim, double cpu_t) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "ray %zu (from primary %u): o = (%.9g, %.9g, %.9g), d = (%.9g, %.9g, %.9g), tmax %.9g: device "
                  "triangle %lld at t %.9g, CPU triangle %lld at t %.9g",
                  i, r.src, r.o[0], r.o[1], r.o[2], r.d[0], r.d[1], r.d[2], r.tmax, (long long)dev_prim, dev_t,
                  (long long)cpu_prim, cpu_t);
    return buf;
}

BatchAgreement check_closest(const Bvh& reference, const BvhTriangles& device_tris,
                             const std::vector<BatchRay>& rays, const std::vector<Hit>& hits, std::size_t check) {
    const auto idx = checked_rays(rays.size(), check);
    std::vector<CpuHit> cpu(idx.size());
    parallel_for(idx.size(), [&](std::size_t k) { cpu[k] = cpu_closest_hit(reference, rays[idx[k]]); });
    BatchAgreement a;
    a.checked = idx.size();
    for (std::size_t k = 0; k < idx.size(); ++k) {
        const Hit& h = hits[idx[k]];
        const std::int64_t prim = h.tri < 0 ? -1 : std::int64_t(device_tris[std::size_t(h.tri)].prim);
        const CpuHit& c = cpu[k];
        const BatchRay& r = rays[idx[k]];
        // Float error in t grows with the coordinates' magnitude, not with t alone.
        const double scale = c.t + std::max({std::abs(r.o[0]), std::abs(r.o[1]), std::abs(r.o[2])});
        if (prim == c.prim) {
            ++a.identical;
            if (prim >= 0) a.max_dt = std::max(a.max_dt, std::abs(double(h.t) - c.t));
        } else if (prim >= 0 && c.prim >= 0 && std::abs(double(h.t) - c.t) <= kTieTolerance * scale) {
            ++a.ties;
        } else if ((c.prim >= 0 && c.t <= kNearOrigin * scale) || (prim >= 0 && double(h.t) <= kNearOrigin * scale)) {
            ++a.near_origin;
        } else {
            if (!a.mismatched++) a.first_mismatch = mismatch_report(idx[k], r, prim, h.t, c.prim, c.t);
        }
    }
    return a;
}

BatchAgreement check_any(const Bvh& reference, const std::vector<BatchRay>& rays, const std::vector<int>& occluder,
                         std::size_t check) {
    const auto idx = checked_rays(rays.size(), check);
    std::vector<char> cpu(idx.size());
    parallel_for(idx.size(), [&](std::size_t k) { cpu[k] = cpu_any_hit(reference, rays[idx[k]]) >= 0; });
    BatchAgreement a;
    a.checked = idx.size();
    for (std::size_t k = 0; k < idx.size(); ++k) {
        const bool dev = occluder[idx[k]] >= 0;
        const BatchRay& r = rays[idx[k]];
        if (bool(cpu[k]) == dev) {
            ++a.identical;
            continue;
        }
        // Where the two differ, the exact closest occluder tells whether it sits
        // at the origin. That includes t = 0: a secondary ray can start exactly
        // on the surface it leaves (kernels/intersect.cl hit_point), which
        // clpath's t bound rejects and Embree, from tnear 0, reports.
        const CpuHit c = cpu_closest_hit(reference, r, true);
        const double scale = std::max({std::abs(r.o[0]), std::abs(r.o[1]), std::abs(r.o[2])});
        if (c.prim >= 0 && c.t * std::sqrt(double(r.d[0]) * r.d[0] + double(r.d[1]) * r.d[1] + double(r.d[2]) * r.d[2]) <=
                               kNearOrigin * scale) {
            ++a.near_origin;
        } else if (!a.mismatched++) {
            a.first_mismatch = mismatch_report(idx[k], rays[idx[k]], dev ? 1 : -1, 0, cpu[k] ? 1 : -1, 0);
        }
    }
    return a;
}

// Embree's answers in the device's form (Hit.tri indexes the leaf-ordered
// triangles), so check_closest and check_any judge both the same way.
std::vector<std::uint32_t> leaf_index_of_prim(const BvhTriangles& tris) {
    std::vector<std::uint32_t> at(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) at[tris[i].prim] = std::uint32_t(i);
    return at;
}

void take_timing(EmbreeBatch& e, const EmbreeTiming& t) {
    e.ran = true;
    e.best_ms = t.best_ms;
    e.mean_ms = t.mean_ms;
    e.median_ms = median_of(t.pass_ms);
    e.mrays_per_s = t.mrays_per_s;
}

EmbreeBatch embree_closest(EmbreeBaseline& embree, const Bvh& reference, const BvhTriangles& tris,
                           const std::vector<std::uint32_t>& leaf_of, const std::vector<BatchRay>& rays,
                           const RayBenchOptions& o) {
    std::vector<std::int64_t> prim;
    std::vector<float> t;
    EmbreeBatch e;
    e.mode = embree.mode();
    take_timing(e, embree.closest(rays, o.launches, prim, t));
    std::vector<Hit> hits(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits[i].t = t[i];
        hits[i].b1 = hits[i].b2 = 0;
        hits[i].tri = prim[i] < 0 ? -1 : int(leaf_of[std::size_t(prim[i])]);
        e.hits += prim[i] >= 0;
    }
    e.agreement = check_closest(reference, tris, rays, hits, o.check);
    return e;
}

EmbreeBatch embree_any(EmbreeBaseline& embree, const Bvh& reference, const std::vector<BatchRay>& rays,
                       const RayBenchOptions& o) {
    std::vector<char> occluded;
    EmbreeBatch e;
    e.mode = embree.mode();
    take_timing(e, embree.any(rays, o.launches, occluded));
    std::vector<int> occluder(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        occluder[i] = occluded[i] ? 1 : -1;
        e.hits += occluded[i] != 0;
    }
    e.agreement = check_any(reference, rays, occluder, o.check);
    return e;
}

void finish_timing(BatchResult& b) {
    b.best_ms = *std::min_element(b.launch_ms.begin(), b.launch_ms.end());
    double sum = 0;
    for (double ms : b.launch_ms) sum += ms;
    b.mean_ms = sum / double(b.launch_ms.size());
    b.median_ms = median_of(b.launch_ms);
    b.mrays_per_s = b.mean_ms > 0 ? double(b.rays) / (b.mean_ms * 1e-3) * 1e-6 : 0;
}

// How many of the variant's answers (in out) differ, bit for bit, from the built-in kernels' (a).
template <class T>
std::size_t count_differing(Context& ctx, const Buffer& out, const std::vector<T>& a) {
    std::vector<T> b(a.size());
    ctx.read(out, b.data(), a.size() * sizeof(T));
    std::size_t d = 0;
    for (std::size_t i = 0; i < a.size(); ++i) d += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
    return d;
}

}  // namespace

glm::vec3 default_bench_light(const Scene& scene) {
    for (const auto& l : scene.lights)
        if (l.type == PunctualLight::Type::Point) return l.position;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : scene.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    glm::vec3 sum(0);
    double area = 0;
    for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
        if (!emits(scene.materials[scene.triangle_material[t]])) continue;
        const glm::vec3 a = scene.vertices[3 * t], b = scene.vertices[3 * t + 1], c = scene.vertices[3 * t + 2];
        const float w = 0.5f * glm::length(glm::cross(b - a, c - a));
        sum += w * (a + b + c) / 3.0f;
        area += w;
    }
    if (area > 0) return sum / float(area) - glm::vec3(0, 0.01f * (hi.y - lo.y), 0);
    return {0.5f * (lo.x + hi.x), hi.y + 0.5f * (hi.y - lo.y), 0.5f * (lo.z + hi.z)};
}

RayBenchResult run_ray_bench(Context& ctx, const Scene& scene, const RayBenchOptions& o,
                             const std::function<void(const std::string&)>& log) {
    auto say = [&](const std::string& s) {
        if (log) log(s);
    };
    constexpr int tile = int(CLP_BATCH_TILE);
    if (o.width <= 0 || o.height <= 0 || o.width % tile || o.height % tile)
        throw Error("ray batches: width and height must be positive multiples of " + std::to_string(tile) +
                    " (rays come in " + std::to_string(tile) + "x" + std::to_string(tile) + "-pixel tiles), got " +
                    std::to_string(o.width) + "x" + std::to_string(o.height));
    if (o.launches < 1) throw Error("ray batches: at least one timed launch is needed");
    if (!scene.instances.empty())
        throw Error("bench rays: scene '" + scene.name +
                    "' places meshes by instances, which bench rays does not walk (it times the one-level "
                    "BVH; bench instances times the two-level walk)");
    if (scene.triangle_count() == 0) throw Error("scene '" + scene.name + "' has no triangles");
    if (o.accel == Accel::Flat && scene.triangle_object.size() != scene.triangle_count())
        throw Error("internal: scene '" + scene.name + "' has no object id for every triangle (needed by flat)");
    if (o.workgroup > ctx.device().max_work_group)
        throw Error("ray batches: work-group size " + std::to_string(o.workgroup) + " exceeds " + ctx.device().name +
                    "'s limit of " + std::to_string(ctx.device().max_work_group));
    Camera camera = scene.camera;
    camera.width = o.width;
    camera.height = o.height;
    const CameraData cam = camera_data(camera);

    RayBenchResult res;
    res.scene = scene.name;
    res.triangles = scene.triangle_count();
    res.accel = o.accel;
    res.light = o.light ? *o.light : default_bench_light(scene);
    res.device = ctx.device().name;

    const Bvh structure = build_accel(o.accel, scene.vertices, scene.triangle_object, o.bvh);
    res.structure = structure.stats;
    const KernelCode code = kernel_code(ctx.device());
    const std::vector<unsigned char> node_bytes = device_nodes(o.accel, structure, node_layout(code, false));
    res.structure_bytes = node_bytes.size() + structure.triangles.size() * sizeof(TriVerts);
    // The CPU reference walks a BVH; for the flat structure it is a second
    // structure, so the check also compares flat against BVH.
    std::optional<Bvh> own_reference;
    if (o.accel != Accel::Bvh) own_reference = build_bvh(scene.vertices, o.bvh);
    const Bvh& reference = own_reference ? *own_reference : structure;
    say(std::string(accel_name(o.accel)) + ": " + describe(structure.stats));

    const std::size_t n = std::size_t(o.width) * std::size_t(o.height) * kSamplesPerPixel;
    ctx.check_fits({{"acceleration nodes", node_bytes.size()},
                    {"triangles", structure.triangles.size() * sizeof(TriVerts)},
                    {"primary rays", n * sizeof(BatchRay)},
                    {"primary hits", n * sizeof(Hit)},
                    {"secondary rays", n * sizeof(BatchRay)},
                    {"secondary hits", n * sizeof(Hit)},
                    {"hit list", n * sizeof(std::uint32_t)},
                    {"the variant's answers", !o.ab.empty() ? n * sizeof(Hit) : 0}});
    Buffer nodes = ctx.buffer(node_bytes.size(), CL_MEM_READ_ONLY, "acceleration nodes", node_bytes.data());
    Buffer tris = ctx.buffer(structure.triangles.size() * sizeof(TriVerts), CL_MEM_READ_ONLY, "triangles",
                             structure.triangles.data());
    Buffer cam_buf = ctx.buffer(sizeof cam, CL_MEM_READ_ONLY, "camera", &cam);
    Buffer primary = ctx.buffer(n * sizeof(BatchRay), CL_MEM_READ_WRITE, "primary rays");
    Buffer primary_hits = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "primary hits");
    Buffer secondary = ctx.buffer(n * sizeof(BatchRay), CL_MEM_READ_WRITE, "secondary rays");
    Buffer secondary_hits = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "secondary hits");
    Buffer src = ctx.buffer(n * sizeof(std::uint32_t), CL_MEM_READ_WRITE, "hit list");
    // Hit is the larger answer: any-hit kernels write one int per ray.
    Buffer variant_out;
    if (!o.ab.empty()) variant_out = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "the variant's answers");

    const ProgramSpec spec = ray_batch_program(o.accel, code);
    const std::string source = program_source(spec.roots), options = spec.options;
    BuildResult built = build_program(ctx, source, options);
    say(std::string("kernels ") + (built.from_cache ? "loaded from cache" : "compiled") + " in " +
        std::to_string(built.seconds) + " s");
    Kernel make_primary = ctx.kernel(built.program.get(), "batch_primary_rays");
    Kernel make_secondary = ctx.kernel(built.program.get(), "batch_secondary_rays");
    Kernel closest = ctx.kernel(built.program.get(), "batch_trace_closest");
    Kernel any = ctx.kernel(built.program.get(), "batch_trace_any");
    for (const Kernel* k : {&make_primary, &make_secondary, &closest, &any})
        res.kernels.push_back(kernel_info(*k, ctx.device().device));

    if (o.on_structure) o.on_structure(source, options, node_bytes, structure.triangles);

    // The variant: the same root files and options, some files replaced, options added (o.ab).
    std::optional<BuildResult> variant;
    std::optional<Kernel> closest_v, any_v;
    if (!o.ab.empty()) {
        variant = build_program(ctx, variant_source(spec.roots, o.ab), variant_options(options, o.ab));
        closest_v.emplace(ctx.kernel(variant->program.get(), "batch_trace_closest"));
        any_v.emplace(ctx.kernel(variant->program.get(), "batch_trace_any"));
        say(std::string("variant kernels ") + (variant->from_cache ? "loaded from cache" : "compiled") + " in " +
            std::to_string(variant->seconds) + " s");
    }

    // The CPU baselines trace the same rays after the device, each batch in
    // turn: Embree in its default mode, then robust.
    std::vector<std::unique_ptr<EmbreeBaseline>> embree;
    std::vector<std::uint32_t> leaf_of;
    if (o.embree) {
        for (EmbreeMode mode : kEmbreeModes) {
            if (mode == EmbreeMode::Robust && !o.embree_robust) continue;
            auto e = make_embree_baseline(scene.vertices, mode);
            if (!e) break;
            res.embree[int(mode)] = e->describe();
            say("CPU baseline: " + res.embree[int(mode)]);
            embree.push_back(std::move(e));
        }
        if (!embree.empty()) leaf_of = leaf_index_of_prim(structure.triangles);
    }

    // Traces b.rays rays into out with trace kernel k: one warm-up launch,
    // then the timed ones; every launch writes the same results. With a
    // variant v (the same arguments, its own output), each launch of k is
    // paired with one of v, which goes first alternating.
    auto time_batch = [&](BatchResult& b, Kernel& k, std::optional<Kernel>& v, const Buffer& rays, const Buffer& out) {
        const auto count = std::uint32_t(b.rays);
        k.arg(0, nodes).arg(1, tris).arg(2, rays).arg(3, out).arg(4, count);
        if (v) v->arg(0, nodes).arg(1, tris).arg(2, rays).arg(3, variant_out).arg(4, count);
        for (int l = 0; l <= o.launches; ++l) {
            double t[2] = {0, 0};  // built-in, variant
            for (int j = 0; j < (v ? 2 : 1); ++j) {
                const int which = v ? (l + j) % 2 : 0;
                cl_event ev = ctx.launch(which ? *v : k, b.rays, o.workgroup, true);
                t[which] = ev ? event_seconds(ev) : 0.0;
            }
            if (l == 0) continue;
            b.launch_ms.push_back(t[0] * 1e3);
            if (v && t[1] > 0) b.ab.ratios.push_back(t[0] / t[1]);
        }
        finish_timing(b);
        if (!b.ab.ratios.empty()) finish_ab(b.ab);
    };

    make_primary.arg(0, cam_buf).arg(1, primary);
    ctx.launch(make_primary, n, 0);
    BatchResult prim;
    prim.name = "primary";
    prim.rays = n;
    say("primary: tracing " + std::to_string(n) + " rays");
    time_batch(prim, closest, closest_v, primary, primary_hits);
    std::vector<BatchRay> primary_rays(n);
    std::vector<Hit> primary_result(n);
    ctx.read(primary, primary_rays);
    ctx.read(primary_hits, primary_result);
    if (closest_v) prim.ab.differing = count_differing(ctx, variant_out, primary_result);
    std::vector<std::uint32_t> hit_list;
    for (std::size_t i = 0; i < n; ++i)
        if (primary_result[i].tri >= 0) hit_list.push_back(std::uint32_t(i));
    prim.hits = hit_list.size();
    prim.agreement = check_closest(reference, structure.triangles, primary_rays, primary_result, o.check);
    if (o.on_traced) o.on_traced(RayBatchKind::Primary, primary_rays, closest_hit_results(primary_result));
    for (auto& e : embree)
        prim.embree[int(e->mode())] = embree_closest(*e, reference, structure.triangles, leaf_of, primary_rays, o);
    res.batches.push_back(prim);
    if (!hit_list.empty()) ctx.write(src, hit_list.data(), hit_list.size() * sizeof(std::uint32_t));
    const std::uint32_t m = std::uint32_t(hit_list.size());

    auto make_rays = [&](std::uint32_t diffuse) {
        make_secondary.arg(0, tris).arg(1, primary).arg(2, primary_hits).arg(3, src).arg(4, m);
        make_secondary.arg(5, res.light.x).arg(6, res.light.y).arg(7, res.light.z).arg(8, diffuse).arg(9, o.seed);
        make_secondary.arg(10, secondary);
        ctx.launch(make_secondary, m, 0);
    };

    BatchResult shadow;
    shadow.name = "shadow";
    shadow.rays = m;
    if (m > 0) {
        make_rays(0);
        say("shadow: tracing " + std::to_string(m) + " rays");
        time_batch(shadow, any, any_v, secondary, secondary_hits);
        std::vector<BatchRay> rays(m);
        std::vector<int> occluder(m);
        ctx.read(secondary, rays);
        ctx.read(secondary_hits, occluder.data(), m * sizeof(int));
        if (any_v) shadow.ab.differing = count_differing(ctx, variant_out, occluder);
        for (int x : occluder) shadow.hits += x >= 0;
        shadow.agreement = check_any(reference, rays, occluder, o.check);
        if (o.on_traced) o.on_traced(RayBatchKind::Shadow, rays, any_hit_results(occluder));
        for (auto& e : embree) shadow.embree[int(e->mode())] = embree_any(*e, reference, rays, o);
    } else if (o.on_traced) {
        o.on_traced(RayBatchKind::Shadow, {}, {});
    }
    res.batches.push_back(shadow);

    BatchResult diffuse;
    diffuse.name = "diffuse";
    diffuse.rays = m;
    if (m > 0) {
        make_rays(1);
        say("diffuse: tracing " + std::to_string(m) + " rays");
        time_batch(diffuse, closest, closest_v, secondary, secondary_hits);
        std::vector<BatchRay> rays(m);
        std::vector<Hit> hits(m);
        ctx.read(secondary, rays);
        ctx.read(secondary_hits, hits);
        if (closest_v) diffuse.ab.differing = count_differing(ctx, variant_out, hits);
        for (const auto& h : hits) diffuse.hits += h.tri >= 0;
        diffuse.agreement = check_closest(reference, structure.triangles, rays, hits, o.check);
        if (o.on_traced) o.on_traced(RayBatchKind::Diffuse, rays, closest_hit_results(hits));
        for (auto& e : embree)
            diffuse.embree[int(e->mode())] = embree_closest(*e, reference, structure.triangles, leaf_of, rays, o);
    } else if (o.on_traced) {
        o.on_traced(RayBatchKind::Diffuse, {}, {});
    }
    res.batches.push_back(diffuse);
    return res;
}

std::string describe(const BatchResult& b) {
    char buf[512];
    const BatchAgreement& a = b.agreement;
    std::snprintf(buf, sizeof buf,
                  "%s: %zu rays (%zu hit), kernel %.3f ms mean / %.3f ms best, %.2f Mrays/s; CPU check: %zu rays, "
                  "%.4f %% identical hits, %zu ties, %zu at the origin, %zu mismatched, max |dt| %.2g",
                  b.name.c_str(), b.rays, b.hits, b.mean_ms, b.best_ms, b.mrays_per_s, a.checked,
                  a.identical_percent(), a.ties, a.near_origin, a.mismatched, a.max_dt);
    return a.first_mismatch.empty() ? std::string(buf) : std::string(buf) + "\n  first mismatch: " + a.first_mismatch;
}

std::string describe_embree(const BatchResult& b, EmbreeMode mode) {
    const EmbreeBatch& e = b.embree_in(mode);
    const BatchAgreement& a = e.agreement;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "  Embree %s mode: %zu hit, %.3f ms mean / %.3f ms best, %.2f Mrays/s, clpath/Embree %.3f; CPU check: "
                  "%zu rays, %.4f %% identical hits, %zu ties, %zu at the origin, %zu mismatched",
                  embree_mode_name(mode), e.hits, e.mean_ms, e.best_ms, e.mrays_per_s, b.over_embree(mode), a.checked,
                  a.identical_percent(), a.ties, a.near_origin, a.mismatched);
    return a.first_mismatch.empty() ? std::string(buf) : std::string(buf) + "\n  Embree's first mismatch: " + a.first_mismatch;
}

std::string describe_ab(const BatchResult& b) {
    if (!b.ab.ran) return "";
    return "  A/B: " + describe_ab_ratios(b.ab) + "; answers differ for " + std::to_string(b.ab.differing) + " rays";
}

}  // namespace clpath
