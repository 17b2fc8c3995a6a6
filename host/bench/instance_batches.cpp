#include "bench/instance_batches.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "bench/embree_baseline.hpp"
#include "bench/ray_batches.hpp"
#include "bvh/accel.hpp"
#include "cl/embedded_sources.hpp"
#include "cl/program.hpp"
#include "render/kernel_programs.hpp"
#include "render/prepared_scene.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

constexpr std::size_t kSamplesPerPixel = CLP_BATCH_SAMPLES;

// A batch's rays and, per ray, the two-level walk's answer: t of the
// closest hit (or 1 for an occluded shadow ray), negative for none.
struct TracedBatch {
    std::string name;
    bool any_hit = false;
    std::vector<BatchRay> rays;
    std::vector<float> answer;
    std::vector<float> closest;  // any-hit batches: the two-level walk's closest hit (t, or negative), to judge differences
};

// How tracer answers b compare with the two-level walk's a (bench/ray_batches.hpp's categories).
void compare(const TracedBatch& a, const std::vector<float>& b, TracerPass& p) {
    for (std::size_t i = 0; i < a.rays.size(); ++i) {
        const bool ha = a.answer[i] >= 0, hb = b[i] >= 0;
        p.hits += hb;
        const BatchRay& r = a.rays[i];
        if (a.any_hit) {
            // A shadow ray occluded only by what lies at its origin: the
            // surface it leaves, which each tracer guards against its own way.
            if (ha == hb) continue;
            const double mag = std::max({std::abs(r.o[0]), std::abs(r.o[1]), std::abs(r.o[2])});
            const double len = std::sqrt(double(r.d[0]) * r.d[0] + double(r.d[1]) * r.d[1] + double(r.d[2]) * r.d[2]);
            if (a.closest[i] >= 0 && a.closest[i] * len <= kNearOrigin * mag) ++p.near_origin;
            else ++p.differing;
            continue;
        }
        const double scale =
            std::max({std::abs(r.o[0]), std::abs(r.o[1]), std::abs(r.o[2])}) + std::max(0.0f, std::max(a.answer[i], b[i]));
        if (ha == hb && (!ha || std::abs(double(a.answer[i]) - b[i]) <= kTieTolerance * scale)) continue;
        if ((ha && a.answer[i] <= kNearOrigin * scale) || (hb && b[i] <= kNearOrigin * scale)) ++p.near_origin;
        else ++p.differing;
    }
}

void finish(TracerPass& p, const std::vector<double>& ms, std::size_t rays) {
    p.ran = true;
    double sum = 0;
    p.best_ms = ms.empty() ? 0 : *std::min_element(ms.begin(), ms.end());
    for (double x : ms) sum += x;
    p.mean_ms = ms.empty() ? 0 : sum / double(ms.size());
    p.mrays_per_s = p.mean_ms > 0 ? double(rays) / (p.mean_ms * 1e-3) * 1e-6 : 0;
}

// A point light above the placed geometry's world box (instances' boxes from their meshes' corners).
glm::vec3 light_above(const Scene& scene) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : scene.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
    std::vector<std::pair<glm::vec3, glm::vec3>> box(scene.meshes.size(), {glm::vec3(INFINITY), glm::vec3(-INFINITY)});
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const auto& v : scene.meshes[m].vertices)
            box[m].first = glm::min(box[m].first, v), box[m].second = glm::max(box[m].second, v);
    for (const auto& in : scene.instances)
        for (int k = 0; k < 8; ++k) {
            const auto& [a, b] = box[in.mesh];
            const glm::vec3 c((k & 1) ? b.x : a.x, (k & 2) ? b.y : a.y, (k & 4) ? b.z : a.z);
            const glm::vec3 w(in.object_to_world * glm::vec4(c, 1.0f));
            lo = glm::min(lo, w), hi = glm::max(hi, w);
        }
    const glm::vec3 e = hi - lo;
    return {0.5f * (lo.x + hi.x), hi.y + 0.5f * std::max({e.x, e.y, e.z}), 0.5f * (lo.z + hi.z)};
}

// One device structure with its batch kernels.
struct DeviceTracer {
    Buffer nodes, tris;
    BuildResult built;
    Kernel closest, any;
};

DeviceTracer device_tracer(Context& ctx, const std::vector<unsigned char>& node_bytes, const BvhTriangles& tris,
                           const ProgramSpec& spec) {
    DeviceTracer d{ctx.buffer(node_bytes.size(), CL_MEM_READ_ONLY, "acceleration nodes", node_bytes.data()),
                   ctx.buffer(tris.size() * sizeof(TriVerts), CL_MEM_READ_ONLY, "triangles", tris.data()),
                   build_program(ctx, program_source(spec.roots), spec.options),
                   {},
                   {}};
    d.closest = ctx.kernel(d.built.program.get(), "batch_trace_closest");
    d.any = ctx.kernel(d.built.program.get(), "batch_trace_any");
    return d;
}

}  // namespace

const char* instance_tracer_name(InstanceTracer t) {
    static const char* names[kInstanceTracers] = {"clpath instanced",         "clpath flattened",
                                                  "Embree instanced default", "Embree instanced robust",
                                                  "Embree flattened default", "Embree flattened robust"};
    return names[std::size_t(t)];
}

double InstanceBatch::ratio(InstanceTracer t) const {
    const TracerPass& p = of(t);
    return p.ran && p.mrays_per_s > 0 ? of(InstanceTracer::Instanced).mrays_per_s / p.mrays_per_s : 0;
}

InstanceBenchResult run_instance_bench(Context& ctx, const Scene& scene, const InstanceBenchOptions& o,
                                       const std::function<void(const std::string&)>& log) {
    auto say = [&](const std::string& s) {
        if (log) log(s);
    };
    constexpr int tile = int(CLP_BATCH_TILE);
    if (o.width <= 0 || o.height <= 0 || o.width % tile || o.height % tile)
        throw Error("bench instances: width and height must be positive multiples of " + std::to_string(tile) +
                    ", got " + std::to_string(o.width) + "x" + std::to_string(o.height));
    if (o.launches < 1) throw Error("bench instances: at least one timed launch is needed");
    if (scene.instances.empty())
        throw Error("bench instances: scene '" + scene.name +
                    "' places no mesh by instances (bench rays times scenes of one level)");
    InstanceBenchResult res;
    res.scene = scene.name;
    res.device = ctx.device().name;
    res.instances = scene.instances.size();
    res.placed_triangles = scene.placed_triangle_count();
    res.stored_triangles = scene.triangle_count();
    for (const auto& m : scene.meshes) res.stored_triangles += m.triangle_count();
    res.light = o.light ? *o.light : light_above(scene);

    const TwoLevelBvh two = scene_two_level(scene, o.bvh);
    res.two_level = two.stats;
    const auto* node_data = reinterpret_cast<const unsigned char*>(two.nodes.data());
    const std::vector<unsigned char> two_bytes(node_data, node_data + two.nodes.size() * sizeof(Bvh4Node128));
    res.instanced_bytes = two_bytes.size() + two.triangles.size() * sizeof(TriVerts);
    say("two-level BVH: " + std::to_string(res.instances) + " instances, " + std::to_string(res.instanced_bytes) +
        " bytes, top level built in " + std::to_string(two.stats.top_build_ms) + " ms");

    const std::size_t n = std::size_t(o.width) * std::size_t(o.height) * kSamplesPerPixel;
    ctx.check_fits({{"two-level nodes", two_bytes.size()},
                    {"triangles", two.triangles.size() * sizeof(TriVerts)},
                    {"rays (primary, shadow, diffuse)", 3 * n * sizeof(BatchRay)},
                    {"hits and their instances", n * (sizeof(Hit) + sizeof(int))},
                    {"hit list", n * sizeof(std::uint32_t)}});
    const KernelCode code = kernel_code(ctx.device());
    const ProgramSpec spec = ray_batch_program(Accel::Bvh, code, true);
    DeviceTracer inst = device_tracer(ctx, two_bytes, two.triangles, spec);
    Kernel make_primary = ctx.kernel(inst.built.program.get(), "batch_primary_rays");
    Kernel make_secondary = ctx.kernel(inst.built.program.get(), "batch_secondary_rays");

    Camera camera = scene.camera;
    camera.width = o.width;
    camera.height = o.height;
    const CameraData cam = camera_data(camera);
    Buffer cam_buf = ctx.buffer(sizeof cam, CL_MEM_READ_ONLY, "camera", &cam);
    Buffer ray_buf[3] = {ctx.buffer(n * sizeof(BatchRay), CL_MEM_READ_WRITE, "primary rays"),
                         ctx.buffer(n * sizeof(BatchRay), CL_MEM_READ_WRITE, "shadow rays"),
                         ctx.buffer(n * sizeof(BatchRay), CL_MEM_READ_WRITE, "diffuse rays")};
    Buffer hits = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "hits");
    Buffer insts = ctx.buffer(n * sizeof(int), CL_MEM_READ_WRITE, "hit instances");
    Buffer primary_hits = ctx.buffer(n * sizeof(Hit), CL_MEM_READ_WRITE, "primary hits");
    Buffer primary_insts = ctx.buffer(n * sizeof(int), CL_MEM_READ_WRITE, "primary hit instances");
    Buffer src = ctx.buffer(n * sizeof(std::uint32_t), CL_MEM_READ_WRITE, "hit list");

    // Times a batch (one warm-up launch, then o.launches) on one device structure; answers into out.
    auto time_device = [&](DeviceTracer& d, bool any_hit, const Buffer& rays, std::uint32_t count, const Buffer& out,
                           const Buffer* out_insts, TracerPass& pass) {
        Kernel& k = any_hit ? d.any : d.closest;
        k.arg(0, d.nodes).arg(1, d.tris).arg(2, rays).arg(3, out).arg(4, count);
        if (out_insts) k.arg(5, *out_insts);
        std::vector<double> ms;
        for (int l = 0; l <= o.launches; ++l) {
            cl_event ev = ctx.launch(k, count, o.workgroup, true);
            const double s = ev ? event_seconds(ev) : 0.0;
            if (l > 0) ms.push_back(s * 1e3);
        }
        finish(pass, ms, count);
    };
    auto closest_answers = [&](const Buffer& out, std::size_t count) {
        std::vector<Hit> h(count);
        ctx.read(out, h);
        std::vector<float> a(count);
        for (std::size_t i = 0; i < count; ++i) a[i] = h[i].tri >= 0 ? h[i].t : -1.0f;
        return a;
    };
    auto any_answers = [&](const Buffer& out, std::size_t count) {
        std::vector<int> occ(count);
        ctx.read(out, occ.data(), count * sizeof(int));
        std::vector<float> a(count);
        for (std::size_t i = 0; i < count; ++i) a[i] = occ[i] >= 0 ? 1.0f : -1.0f;
        return a;
    };

    // The batches, traced by the two-level walk; the secondary rays start at its primary hits.
    make_primary.arg(0, cam_buf).arg(1, ray_buf[0]);
    ctx.launch(make_primary, n, 0);
    std::vector<TracedBatch> traced(3);
    std::vector<InstanceBatch> batches(3);
    const char* names[3] = {"primary", "shadow", "diffuse"};
    std::uint32_t count[3] = {std::uint32_t(n), 0, 0};
    for (int b = 0; b < 3; ++b) {
        traced[b].name = batches[b].name = names[b];
        traced[b].any_hit = b == 1;
        if (b == 1) {
            std::vector<Hit> ph(n);
            ctx.read(primary_hits, ph);
            std::vector<std::uint32_t> list;
            for (std::size_t i = 0; i < n; ++i)
                if (ph[i].tri >= 0) list.push_back(std::uint32_t(i));
            if (!list.empty()) ctx.write(src, list);
            count[1] = count[2] = std::uint32_t(list.size());
        }
        if (b > 0 && count[b] > 0) {
            make_secondary.arg(0, inst.tris).arg(1, ray_buf[0]).arg(2, primary_hits).arg(3, src).arg(4, count[b]);
            make_secondary.arg(5, res.light.x).arg(6, res.light.y).arg(7, res.light.z).arg(8, std::uint32_t(b == 2));
            make_secondary.arg(9, o.seed).arg(10, ray_buf[b]).arg(11, inst.nodes).arg(12, primary_insts);
            ctx.launch(make_secondary, count[b], 0);
        }
        batches[b].rays = count[b];
        traced[b].rays.resize(count[b]);
        if (count[b] == 0) continue;
        say(std::string(names[b]) + ": tracing " + std::to_string(count[b]) + " rays");
        TracerPass& p = batches[b].by[std::size_t(InstanceTracer::Instanced)];
        const Buffer& out = b == 0 ? primary_hits : hits;
        time_device(inst, b == 1, ray_buf[b], count[b], out, b == 1 ? nullptr : (b == 0 ? &primary_insts : &insts), p);
        ctx.read(ray_buf[b], traced[b].rays);
        traced[b].answer = b == 1 ? any_answers(out, count[b]) : closest_answers(out, count[b]);
        for (float a : traced[b].answer) p.hits += a >= 0;
        if (b == 1) {  // the closest hits of the shadow rays too, untimed
            inst.closest.arg(0, inst.nodes).arg(1, inst.tris).arg(2, ray_buf[1]).arg(3, hits).arg(4, count[1]);
            inst.closest.arg(5, insts);
            ctx.launch(inst.closest, count[1], o.workgroup);
            traced[1].closest = closest_answers(hits, count[1]);
        }
    }

    // The same rays through the one-level BVH over the flattened scene.
    std::unique_ptr<Scene> flat;
    if (res.placed_triangles > o.flatten_limit) {
        res.not_flattened = std::to_string(res.placed_triangles) + " placed triangles, more than the " +
                            std::to_string(o.flatten_limit) + " flattened for comparison";
    } else {
        flat = std::make_unique<Scene>(flatten_instances(scene, o.flatten_limit));
        const Bvh bvh = build_accel(Accel::Bvh, flat->vertices, flat->triangle_object, o.bvh);
        const std::vector<unsigned char> flat_bytes = device_nodes(Accel::Bvh, bvh, node_layout(code, false));
        res.flattened = true;
        res.flattened_build_ms = bvh.stats.build_ms;
        res.flattened_bytes = flat_bytes.size() + bvh.triangles.size() * sizeof(TriVerts);
        say("flattened: " + describe(bvh.stats));
        ctx.check_fits({{"flattened nodes", flat_bytes.size()},
                        {"flattened triangles", bvh.triangles.size() * sizeof(TriVerts)}});
        DeviceTracer one = device_tracer(ctx, flat_bytes, bvh.triangles, ray_batch_program(Accel::Bvh, code));
        for (int b = 0; b < 3; ++b) {
            if (count[b] == 0) continue;
            TracerPass& p = batches[b].by[std::size_t(InstanceTracer::Flattened)];
            time_device(one, b == 1, ray_buf[b], count[b], hits, nullptr, p);
            compare(traced[b], b == 1 ? any_answers(hits, count[b]) : closest_answers(hits, count[b]), p);
        }
    }

    // Embree over the instances, then flattened; each in its default mode, then robust.
    if (o.embree && embree_built_in()) {
        std::vector<const std::vector<glm::vec3>*> meshes;
        std::vector<std::pair<std::uint32_t, glm::mat4>> placements;
        const bool flat_part = scene.triangle_count() > 0;
        if (flat_part) meshes.push_back(&scene.vertices), placements.push_back({0, glm::mat4(1.0f)});
        for (const auto& m : scene.meshes) meshes.push_back(&m.vertices);
        for (const auto& in : scene.instances)
            placements.push_back({in.mesh + (flat_part ? 1u : 0u), in.object_to_world});
        for (int shape = 0; shape < 2; ++shape) {
            if (shape == 1 && !flat) break;
            for (EmbreeMode mode : kEmbreeModes) {
                const auto t = InstanceTracer(2 + 2 * shape + (mode == EmbreeMode::Robust ? 1 : 0));
                auto e = shape == 0 ? make_embree_instanced_baseline(meshes, placements, mode)
                                    : make_embree_baseline(flat->vertices, mode);
                res.baselines[std::size_t(t)] = e->describe();
                say(std::string(instance_tracer_name(t)) + ": " + res.baselines[std::size_t(t)]);
                for (int b = 0; b < 3; ++b) {
                    if (count[b] == 0) continue;
                    TracerPass& p = batches[b].by[std::size_t(t)];
                    std::vector<float> answer(count[b]);
                    EmbreeTiming timing;
                    if (b == 1) {
                        std::vector<char> occluded;
                        timing = e->any(traced[b].rays, o.launches, occluded);
                        for (std::size_t i = 0; i < answer.size(); ++i) answer[i] = occluded[i] ? 1.0f : -1.0f;
                    } else {
                        std::vector<std::int64_t> prim;
                        std::vector<float> tt;
                        timing = e->closest(traced[b].rays, o.launches, prim, tt);
                        for (std::size_t i = 0; i < answer.size(); ++i) answer[i] = prim[i] >= 0 ? tt[i] : -1.0f;
                    }
                    finish(p, timing.pass_ms, count[b]);
                    compare(traced[b], answer, p);
                }
            }
        }
    }
    res.batches = std::move(batches);
    return res;
}

std::string describe(const InstanceBatch& b) {
    const TracerPass& own = b.of(InstanceTracer::Instanced);
    char buf[320];
    std::snprintf(buf, sizeof buf, "%s: %zu rays (%zu hit), clpath instanced %.3f ms mean / %.3f ms best, %.2f Mrays/s",
                  b.name.c_str(), b.rays, own.hits, own.mean_ms, own.best_ms, own.mrays_per_s);
    std::string s = buf;
    for (std::size_t t = 1; t < kInstanceTracers; ++t) {
        const TracerPass& p = b.by[t];
        if (!p.ran) continue;
        std::snprintf(buf, sizeof buf,
                      "\n  %s: %.3f ms mean, %.2f Mrays/s, clpath instanced/this %.3f; %zu hit, %zu rays differ, %zu "
                      "at the origin",
                      instance_tracer_name(InstanceTracer(t)), p.mean_ms, p.mrays_per_s, b.ratio(InstanceTracer(t)),
                      p.hits, p.differing, p.near_origin);
        s += buf;
    }
    return s;
}

}  // namespace clpath
