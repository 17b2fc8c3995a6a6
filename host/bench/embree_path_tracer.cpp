#include "bench/embree_path_tracer.hpp"

#include <fstream>

#include "render/prepared_scene.hpp"
#include "util/error.hpp"

#if CLPATH_WITH_EMBREE
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <system_error>
#include <thread>

#include <embree3/rtcore.h>

#include "bench/cpu_estimator.hpp"
#include "bench/embree_scene.hpp"
#include "render/kernel_features.hpp"
#endif

namespace clpath {

std::string cpu_model_name() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon == std::string::npos) break;
            std::string name = line.substr(colon + 1);
            name.erase(0, name.find_first_not_of(" \t"));
            if (!name.empty()) return name;
        }
    return "an unknown CPU";
}

std::vector<std::string> embree_path_unsupported(const Scene& scene) {
    std::vector<std::string> why;
    if (!scene.instances.empty()) why.push_back("meshes placed by instances");
    static const char* kind_names[] = {"diffuse", "a mirror", "a conductor", "a dielectric", "a glTF metallic-roughness material"};
    std::vector<bool> used(scene.materials.size(), false);
    for (auto m : scene.triangle_material)
        if (m < used.size()) used[m] = true;
    for (std::size_t i = 0; i < used.size(); ++i) {
        if (!used[i]) continue;
        const SceneMaterial& m = scene.materials[i];
        const std::string name = "material '" + (i < scene.material_names.size() ? scene.material_names[i] : std::to_string(i)) + "'";
        if (m.kind != CLP_MAT_DIFFUSE)
            why.push_back(name + " is " + (m.kind < CLP_MAT_KIND_COUNT ? kind_names[m.kind] : "of an unknown kind") +
                          " (only diffuse surfaces are supported)");
        for (int t : m.texture)
            if (t != CLP_NO_TEXTURE) {
                why.push_back(name + " maps a texture");
                break;
            }
        if (m.alpha_mode != CLP_ALPHA_OPAQUE) why.push_back(name + " is not opaque (alpha cut-out or blend)");
    }
    if (!scene.colors.empty()) why.push_back("the mesh has vertex colours");
    if (scene.environment.emits()) why.push_back("the scene has an environment (sky colour or map)");
    return why;
}

#if !CLPATH_WITH_EMBREE

bool embree_path_built_in() { return false; }

std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene&, std::uint32_t, EmbreeMode, int) { return nullptr; }
std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene&, std::shared_ptr<const PreparedScene>,
                                                          std::uint32_t, EmbreeMode, int) {
    return nullptr;
}

#else

bool embree_path_built_in() { return true; }

namespace {

using cpu::max3;
using glm::vec3;

constexpr int kTile = 16;  // pixels per side of the tiles the threads take in turn

class Tracer final : public EmbreePathTracer {
public:
    Tracer(const Scene& scene, std::shared_ptr<const PreparedScene> prepared, std::uint32_t max_depth, EmbreeMode mode,
           int threads)
        : max_depth_(max_depth), prepared_(std::move(prepared)) {
        const auto why = embree_path_unsupported(scene);
        if (!why.empty()) {
            std::string all;
            for (const auto& w : why) all += (all.empty() ? "" : "; ") + w;
            throw Error("the Embree path tracer cannot render this scene as clpath does: " + all);
        }
        // The light table, materials and normals exactly as the renderer
        // uploads them (render/prepared_scene.hpp); of its BVH only the
        // triangles' light indices are read (for MIS at emitters).
        light_of_.assign(scene.triangle_count(), CLP_NO_LIGHT);
        for (const auto& t : prepared_->accel.triangles) light_of_[t.prim] = t.light;
        emission_ = scene_features(scene).emission;  // as the kernels are compiled (CLP_HAS_EMISSION)
        camera_ = camera_data(scene.camera);
        width_ = scene.camera.width;
        height_ = scene.camera.height;
        // What a hit reads of its triangle, in one record: computed once
        // here, as Embree's own renderers keep their meshes' data at hand.
        tris_.resize(scene.triangle_count());
        for (std::size_t t = 0; t < tris_.size(); ++t) {
            const vec3 v0 = scene.vertices[3 * t], v1 = scene.vertices[3 * t + 1], v2 = scene.vertices[3 * t + 2];
            TriangleRecord& r = tris_[t];
            r.v0 = v0;
            r.e1 = v1 - v0;
            r.e2 = v2 - v0;
            r.ng = glm::normalize(glm::cross(v1 - v0, v2 - v0));
            r.material = &prepared_->materials[prepared_->triangle_material[t]];
        }
        embree_ = std::make_unique<EmbreeScene>(scene.vertices, threads, mode);
    }

    EmbreePathRun render(std::uint32_t spp, std::uint32_t seed) override {
        EmbreePathRun run;
        PathSums& out = run.sums;
        out.width = width_;
        out.height = height_;
        out.spp = spp;
        out.sum.assign(std::size_t(width_) * height_ * 3, 0.0);
        out.sum_sq.assign(out.sum.size(), 0.0);
        const int tiles_x = (width_ + kTile - 1) / kTile, tiles = tiles_x * ((height_ + kTile - 1) / kTile);
        std::atomic<int> next{0};
        std::atomic<std::uint64_t> rays{0}, nonfinite{0};
        auto work = [&] {
            const EmbreeThreadFloatMode ftz_daz;
            std::uint64_t my_rays = 0, my_nonfinite = 0;
            for (int tile; (tile = next.fetch_add(1)) < tiles;) {
                const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
                for (int py = y0; py < std::min(height_, y0 + kTile); ++py)
                    for (int px = x0; px < std::min(width_, x0 + kTile); ++px) {
                        const std::uint32_t pixel = std::uint32_t(py) * std::uint32_t(width_) + std::uint32_t(px);
                        double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
                        for (std::uint32_t k = 0; k < spp; ++k) {
                            cpu::Rng rng = cpu::rng_seed(pixel, k, seed);
                            const float jx = cpu::rng_next(&rng), jy = cpu::rng_next(&rng);
                            cpu::Ray ray = cpu::camera_ray(camera_, px, py, jx, jy);
                            cpu::camera_lens(camera_, &rng, ray);
                            vec3 L = integrate(ray, rng, my_rays);
                            if (!std::isfinite(L.x) || !std::isfinite(L.y) || !std::isfinite(L.z)) {
                                ++my_nonfinite;
                                L = vec3(0.0f);
                            }
                            for (int c = 0; c < 3; ++c) {
                                s[c] += L[c];
                                s2[c] += double(L[c]) * L[c];
                            }
                        }
                        for (int c = 0; c < 3; ++c) {
                            out.sum[3 * pixel + c] = s[c];
                            out.sum_sq[3 * pixel + c] = s2[c];
                        }
                    }
            }
            rays += my_rays;
            nonfinite += my_nonfinite;
        };
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::thread> pool;
        try {
            for (int i = 1; i < embree_->threads(); ++i) pool.emplace_back(work);
        } catch (const std::system_error& e) {
            for (auto& th : pool) th.join();
            throw Error(std::string("Embree path tracer: cannot start a thread (") + e.what() + ")");
        }
        work();
        for (auto& th : pool) th.join();
        run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        embree_->check("tracing");
        run.rays = rays;
        run.nonfinite = nonfinite;
        return run;
    }

    std::string describe() const override {
        return std::string("Embree ") + RTC_VERSION_STRING + ", " + describe_embree_mode(embree_->mode()) + ", " +
               std::to_string(embree_->threads()) + " thread" + (embree_->threads() == 1 ? "" : "s") + " on " +
               cpu_model_name() + ", rtcIntersect1/rtcOccluded1 single rays, high-quality BVH, FTZ/DAZ";
    }
    EmbreeMode mode() const override { return embree_->mode(); }

private:
    struct Hit {
        bool hit = false;
        float t = 0, b1 = 0, b2 = 0;
        std::uint32_t prim = 0;
    };

    // r.d is a unit vector (camera rays and BSDF samples are normalised).
    Hit closest(const cpu::Ray& r, std::uint64_t& rays) const {
        ++rays;
        RTCRayHit rh;
        init_embree_ray(rh.ray, r.o, r.d, INFINITY, 1.0f);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        rtcIntersect1(embree_->scene(), &ctx, &rh);
        // Embree has just stored the hit field by field; read back one field
        // at a time (volatile), or the compiler may pair two fields in one
        // 8-byte load, which a 4-byte store cannot forward to (a stall per ray).
        const volatile RTCRayHit& out = rh;
        Hit h;
        if (out.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
        h.hit = true;
        h.t = out.ray.tfar;
        h.b1 = out.hit.u;  // Embree's (u, v) weigh v1 and v2, as the kernels' (b1, b2)
        h.b2 = out.hit.v;
        h.prim = out.hit.primID;
        return h;
    }

    // Anything on o + t d for t up to tmax (d need not be unit).
    bool occluded(vec3 o, vec3 d, float tmax, std::uint64_t& rays) const {
        ++rays;
        RTCRay r;
        init_embree_ray(r, o, d, tmax);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        rtcOccluded1(embree_->scene(), &ctx, &r);
        return r.tfar < 0;  // Embree sets -inf on a hit
    }

    struct Surface {
        vec3 p, err, ng, ns;
        bool front = false;
        const Material* m = nullptr;
    };

    Surface surface_at(const Hit& h, vec3 d) const {
        Surface s;
        const TriangleRecord& t = tris_[h.prim];
        s.ng = t.ng;
        s.front = glm::dot(s.ng, d) < 0.0f;
        s.p = cpu::hit_point_edges(t.v0, t.e1, t.e2, h.b1, h.b2, s.err);
        s.m = t.material;
        s.ns = s.ng;
        if (!prepared_->normals.empty()) {
            const vec3* n = &prepared_->normals[3 * std::size_t(h.prim)];
            const vec3 ns = (1.0f - h.b1 - h.b2) * n[0] + h.b1 * n[1] + h.b2 * n[2];
            const float len = glm::length(ns);
            if (len > 0.0f && std::isfinite(len)) s.ns = ns / len;
        }
        return s;
    }

    // Next-event estimation weighted against BSDF sampling by the power
    // heuristic (kernels/integrator.cl sample_direct).
    vec3 sample_direct(const Surface& s, vec3 wo, cpu::Rng& rng, std::uint64_t& rays) const {
        cpu::LightSample ls;
        const float u0 = cpu::rng_next(&rng), u1 = cpu::rng_next(&rng), u2 = cpu::rng_next(&rng);
        if (!cpu::sample_light(prepared_->lights.data(), prepared_->light_alias.data(),
                               std::uint32_t(prepared_->lights.size()), s.p, u0, u1, u2, ls))
            return vec3(0.0f);
        float bsdf_pdf;
        const vec3 f = cpu::diffuse_eval(cpu::vec3_of(s.m->albedo), s.ng, s.ns, wo, ls.wi, bsdf_pdf);
        if (!(max3(f) > 0.0f) || !(max3(ls.L) > 0.0f)) return vec3(0.0f);
        const vec3 o = cpu::offset_ray_origin(s.p, s.err, s.ng, ls.wi);
        if (ls.infinite ? occluded(o, ls.wi, INFINITY, rays) : occluded(o, ls.to - o, 1.0f, rays)) return vec3(0.0f);
        const float w = ls.delta ? 1.0f : cpu::power_heuristic(ls.pdf, bsdf_pdf);
        return f * ls.L * (w / ls.pdf);
    }

    // kernels/integrator.cl integrate() for the path integrator, diffuse
    // surfaces, no environment, no Russian roulette.
    vec3 integrate(cpu::Ray ray, cpu::Rng& rng, std::uint64_t& rays) const {
        vec3 L(0.0f), beta(1.0f);
        float prev_pdf = 0.0f;
        vec3 prev_p = ray.o;
        bool prev_delta = true;  // what a camera ray sees directly is never light-sampled
        for (std::uint32_t depth = 0;; ++depth) {
            const Hit h = closest(ray, rays);
            if (!h.hit) break;
            const Surface s = surface_at(h, ray.d);
            const Material& m = *s.m;
            const bool emits_here = s.front || (m.flags & CLP_MATF_TWO_SIDED_EMISSION);
            const vec3 Le = emits_here ? cpu::vec3_of(m.emission) : vec3(0.0f);
            if (max3(Le) > 0.0f) {
                float w = 1.0f;
                const std::uint32_t li = light_of_[h.prim];
                if (!prev_delta && li != CLP_NO_LIGHT)
                    w = cpu::power_heuristic(prev_pdf, prepared_->light_alias[li].pmf *
                                                           cpu::triangle_sample_pdf(prepared_->lights[li], prev_p, ray.d, h.t));
                L += beta * w * Le;
            }
            const bool scatters = m.albedo[0] > 0.0f || m.albedo[1] > 0.0f || m.albedo[2] > 0.0f;
            if (depth >= max_depth_ || !scatters) break;
            const vec3 wo = -ray.d;
            if (!prepared_->lights.empty()) L += beta * sample_direct(s, wo, rng, rays);
            // The next ray would reach the deepest vertex, where only emission adds light
            // (kernels/path.cl path_next_ray_gathers): without emitters it is not traced.
            if (!emission_ && depth + 1 >= max_depth_) break;
            const float u1 = cpu::rng_next(&rng), u2 = cpu::rng_next(&rng);
            cpu::rng_next(&rng);  // the kernels draw a third number for every BSDF (diffuse ignores it)
            float pdf;
            const vec3 wi = cpu::diffuse_sample(s.ng, s.ns, wo, u1, u2, pdf);
            // A reflection that points below the geometric surface ends the path.
            if (!(glm::dot(wi, s.ng) * glm::dot(wo, s.ng) > 0.0f)) break;
            beta *= cpu::vec3_of(m.albedo);
            prev_pdf = pdf;
            prev_delta = false;
            prev_p = s.p;
            ray.o = cpu::offset_ray_origin(s.p, s.err, s.ng, wi);
            ray.d = wi;
        }
        return L;
    }

    struct TriangleRecord {
        vec3 v0, e1, e2;  // e1 = v1 - v0, e2 = v2 - v0
        vec3 ng;          // unit geometric normal, counter-clockwise = front
        const Material* material;
    };

    std::uint32_t max_depth_;
    bool emission_ = false;  // some surface emits (environments are refused)
    std::shared_ptr<const PreparedScene> prepared_;
    std::vector<std::uint32_t> light_of_;  // per scene triangle: its light, or CLP_NO_LIGHT
    std::vector<TriangleRecord> tris_;     // per scene triangle
    CameraData camera_{};
    int width_ = 0, height_ = 0;
    std::unique_ptr<EmbreeScene> embree_;
};

}  // namespace

std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene& scene,
                                                          std::shared_ptr<const PreparedScene> prepared,
                                                          std::uint32_t max_depth, EmbreeMode mode, int threads) {
    return std::make_unique<Tracer>(scene, std::move(prepared), max_depth, mode, threads);
}

std::unique_ptr<EmbreePathTracer> make_embree_path_tracer(const Scene& scene, std::uint32_t max_depth, EmbreeMode mode,
                                                          int threads) {
    // The renderer's settings but for what prepare_scene reads (the BVH's), which stay the defaults.
    return make_embree_path_tracer(scene, prepare_scene(scene, RenderSettings{}), max_depth, mode, threads);
}

#endif

}  // namespace clpath
