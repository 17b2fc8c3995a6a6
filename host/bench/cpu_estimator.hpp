#pragma once
// clpath's path-tracing estimator for Lambertian surfaces, written again in
// C++ for a CPU tracer (bench/embree_path_tracer.cpp): the random streams
// (kernels/rng.cl itself, included below), the camera (camera.cl), the diffuse BSDF and its frame
// (materials.cl), the light table's sampling and pdfs (lights.cl), and the
// hit-point error bound and ray offset (intersect.cl). Each function follows
// the kernel function of the same name, so that the CPU tracer draws its
// samples from the same distribution as the kernels; the kernels' files are
// the reference and their comments give the reasons and citations.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <glm/glm.hpp>

#include "shared_structs.h"

namespace clpath::cpu {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;

inline float gamma_bound(int n) { return (float(n) * 0x1.0p-24f) / (1.0f - float(n) * 0x1.0p-24f); }
inline float max3(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
inline glm::vec3 vec3_of(const float* p) { return {p[0], p[1], p[2]}; }

// ---- random numbers: the kernels' own file (hash_u32, Rng, rng_seed, rng_next) ----
#include "rng.cl"

// ---- camera (camera.cl) ----
struct Ray {
    glm::vec3 o, d;
};

inline Ray camera_ray(const CameraData& cam, std::uint32_t px, std::uint32_t py, float jx, float jy) {
    const float x = 2.0f * (float(px) + jx) / float(cam.width) - 1.0f;
    const float y = 1.0f - 2.0f * (float(py) + jy) / float(cam.height);
    return {vec3_of(cam.eye), glm::normalize(vec3_of(cam.forward) + x * vec3_of(cam.right) + y * vec3_of(cam.up))};
}

// ---- sampling (sampling.cl) ----
inline void make_frame(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    const float s = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (s + n.z);
    const float c = n.x * n.y * a;
    t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

inline glm::vec3 sample_cosine_hemisphere(float u1, float u2) {
    const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    float dx = 0, dy = 0;
    if (a != 0.0f || b != 0.0f) {
        float r, phi;
        if (std::fabs(a) > std::fabs(b)) {
            r = a;
            phi = (kPi / 4.0f) * (b / a);
        } else {
            r = b;
            phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
        }
        dx = r * std::cos(phi);
        dy = r * std::sin(phi);
    }
    return {dx, dy, std::sqrt(std::max(0.0f, 1.0f - dx * dx - dy * dy))};
}

inline float spherical_triangle_area(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    return 2.0f * std::atan2(std::fabs(glm::dot(a, glm::cross(b, c))), 1.0f + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
}

inline glm::vec3 orthogonal_part(glm::vec3 v, glm::vec3 n) {
    const glm::vec3 w = v - glm::dot(v, n) * n;
    const float l = glm::length(w);
    return l > 0.0f ? w / l : glm::vec3(0.0f);
}

inline glm::vec3 sample_spherical_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, float area, float u1, float u2) {
    const float cos_alpha =
        std::clamp(glm::dot(glm::normalize(glm::cross(a, b)), glm::normalize(glm::cross(a, c))), -1.0f, 1.0f);
    const float sin_alpha = std::sqrt(std::max(0.0f, 1.0f - cos_alpha * cos_alpha));
    const float a_hat = u1 * area;
    const float sin_a = std::sin(a_hat), cos_a = std::cos(a_hat);
    const float s = sin_a * cos_alpha - cos_a * sin_alpha, t = cos_a * cos_alpha + sin_a * sin_alpha;
    const float u = t - cos_alpha, v = s + sin_alpha * glm::dot(a, b);
    const float q = std::clamp(((v * t - u * s) * cos_alpha - v) / ((v * s + u * t) * sin_alpha), -1.0f, 1.0f);
    const glm::vec3 c_hat = q * a + std::sqrt(std::max(0.0f, 1.0f - q * q)) * orthogonal_part(c, a);
    const float z = 1.0f - u2 * (1.0f - glm::dot(c_hat, b));
    return z * b + std::sqrt(std::max(0.0f, 1.0f - z * z)) * orthogonal_part(c_hat, b);
}

// ---- surfaces (intersect.cl) ----
// e1 = v1 - v0, e2 = v2 - v0, as the kernel computes them (a caller may keep them per triangle).
inline glm::vec3 hit_point_edges(glm::vec3 v0, glm::vec3 e1, glm::vec3 e2, float b1, float b2, glm::vec3& err) {
    const glm::vec3 b1e1 = b1 * e1, b2e2 = b2 * e2;
    const glm::vec3 s = b1e1 + b2e2;
    const glm::vec3 p = v0 + s;
    const glm::vec3 sv = p - s;
    const glm::vec3 rounding = (v0 - sv) + (s - (p - sv));
    err = gamma_bound(6) * (glm::abs(b1e1) + glm::abs(b2e2)) + (1.0f + gamma_bound(4)) * glm::abs(rounding);
    return p;
}
inline glm::vec3 hit_point(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, float b1, float b2, glm::vec3& err) {
    return hit_point_edges(v0, v1 - v0, v2 - v0, b1, b2, err);
}

// std::nextafter(x, +-INFINITY) without the library call (a path tracer
// offsets two ray origins per bounce): one step of the float's bit pattern,
// from zero to the smallest denormal of that sign; infinities and NaN stay.
inline float next_float_up(float x) {
    if (!(x < INFINITY)) return x;
    if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
    std::uint32_t b;
    std::memcpy(&b, &x, 4);
    b = x > 0.0f ? b + 1 : b - 1;
    std::memcpy(&x, &b, 4);
    return x;
}
inline float next_float_away(float x, float dir_sign) {
    return dir_sign > 0.0f ? next_float_up(x) : (dir_sign < 0.0f ? -next_float_up(-x) : x);
}

inline glm::vec3 offset_ray_origin(glm::vec3 p, glm::vec3 err, glm::vec3 n, glm::vec3 w) {
    const float d = glm::dot(glm::abs(n), err);
    glm::vec3 offset = d * n;
    if (glm::dot(w, n) < 0.0f) offset = -offset;
    const glm::vec3 po = p + offset;
    return {next_float_away(po.x, offset.x), next_float_away(po.y, offset.y), next_float_away(po.z, offset.z)};
}

// ---- the diffuse BSDF (materials.cl) ----
struct Frame {
    glm::vec3 t, b, n;
    glm::vec3 to_local(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
    glm::vec3 from_local(glm::vec3 v) const { return v.x * t + v.y * b + v.z * n; }
};

// The shading normal turned to wo's side of the geometric normal (reflective kinds).
inline glm::vec3 scatter_normal(glm::vec3 ng, glm::vec3 ns, glm::vec3 wo) {
    const float s = glm::dot(wo, ng) >= 0.0f ? 1.0f : -1.0f;
    ng *= s;
    ns *= s;
    return glm::dot(ns, ng) < 0.0f ? ng : ns;
}
inline Frame scatter_frame(glm::vec3 ng, glm::vec3 ns, glm::vec3 wo) {
    Frame f;
    f.n = scatter_normal(ng, ns, wo);
    make_frame(f.n, f.t, f.b);
    return f;
}

// Lambert's f |cos theta_i| and the cosine-weighted pdf of wi. Only the
// frame's normal is needed: the local z of a vector is its dot with it.
inline glm::vec3 diffuse_eval(glm::vec3 albedo, glm::vec3 ng, glm::vec3 ns, glm::vec3 wo_w, glm::vec3 wi_w, float& pdf) {
    pdf = 0.0f;
    const glm::vec3 n = scatter_normal(ng, ns, wo_w);
    const float wo_z = glm::dot(wo_w, n), wi_z = glm::dot(wi_w, n);
    if (glm::dot(wi_w, ng) * glm::dot(wo_w, ng) <= 0.0f) return glm::vec3(0.0f);
    if (wo_z <= 0.0f || wi_z <= 0.0f) return glm::vec3(0.0f);
    pdf = wi_z * kInvPi;
    return albedo * (wi_z * kInvPi);
}

// A cosine-weighted direction (world) and its pdf; the weight f cos / pdf is the albedo.
inline glm::vec3 diffuse_sample(glm::vec3 ng, glm::vec3 ns, glm::vec3 wo_w, float u1, float u2, float& pdf) {
    const Frame f = scatter_frame(ng, ns, wo_w);
    const glm::vec3 wi = sample_cosine_hemisphere(u1, u2);
    pdf = wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
    return f.from_local(wi);
}

// ---- lights (lights.cl) ----
inline std::uint32_t pick_light(const AliasEntry* alias, std::uint32_t n, float u) {
    const float x = u * float(n);
    const std::uint32_t i = std::min(std::uint32_t(x), n - 1);
    return (x - float(i)) < alias[i].prob ? i : alias[i].alias;
}

struct LightSample {
    glm::vec3 wi{0}, L{0};
    float pdf = 0;
    glm::vec3 to{0};
    bool infinite = false, delta = false;
};

inline float triangle_solid_angle_dirs(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 n, float area2, glm::vec3 p,
                                       glm::vec3& ua, glm::vec3& ub, glm::vec3& uc) {
    const glm::vec3 da = a - p, db = b - p, dc = c - p;
    const float d2 = std::min(glm::dot(da, da), std::min(glm::dot(db, db), glm::dot(dc, dc)));
    if (!(0.5f * area2 >= CLP_MIN_SPHERICAL_SPREAD * d2)) return 0.0f;
    const float la = glm::length(da), lb = glm::length(db), lc = glm::length(dc);
    if (!(la > 0.0f && lb > 0.0f && lc > 0.0f)) return 0.0f;
    if (!(std::fabs(glm::dot(n, da)) >= CLP_MIN_SPHERICAL_ELEVATION * std::min(la, std::min(lb, lc)))) return 0.0f;
    ua = da / la;
    ub = db / lb;
    uc = dc / lc;
    const float omega = spherical_triangle_area(ua, ub, uc);
    return (omega >= CLP_MIN_SPHERICAL_AREA && omega <= CLP_MAX_SPHERICAL_AREA) ? omega : 0.0f;
}

// Solid-angle pdf (without the pick) of light-sampling, from p, the point at
// distance dist along unit direction d on triangle light l.
inline float triangle_sample_pdf(const Light& l, glm::vec3 p, glm::vec3 d, float dist) {
    const glm::vec3 a = vec3_of(l.a), b = vec3_of(l.b), c = vec3_of(l.c);
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float area2 = glm::length(n);
    glm::vec3 ua, ub, uc;
    const float omega = triangle_solid_angle_dirs(a, b, c, glm::normalize(n), area2, p, ua, ub, uc);
    if (omega > 0.0f) return 1.0f / omega;
    const float cos_l = std::fabs(glm::dot(n, d)) / area2;
    if (!(cos_l > 0.0f)) return 0.0f;
    return dist * dist / (0.5f * area2 * cos_l);
}

inline bool sample_triangle_light(const Light& l, glm::vec3 p, float u1, float u2, LightSample& s) {
    const glm::vec3 a = vec3_of(l.a), b = vec3_of(l.b), c = vec3_of(l.c);
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float area2 = glm::length(n);
    if (!(area2 > 0.0f)) return false;
    float b0, b1;
    glm::vec3 ua, ub, uc;
    const float omega = triangle_solid_angle_dirs(a, b, c, glm::normalize(n), area2, p, ua, ub, uc);
    if (omega > 0.0f) {
        const glm::vec3 w = sample_spherical_triangle(ua, ub, uc, omega, u1, u2);
        const float dn = glm::dot(w, n);
        if (dn == 0.0f) return false;
        const glm::vec3 x = p + (glm::dot(a - p, n) / dn) * w;
        const float inv = 1.0f / (area2 * area2);
        b1 = std::max(0.0f, glm::dot(glm::cross(x - a, c - a), n) * inv);
        float b2 = std::max(0.0f, glm::dot(glm::cross(b - a, x - a), n) * inv);
        const float sum = b1 + b2;
        if (sum > 1.0f) {
            b1 /= sum;
            b2 /= sum;
        }
        b0 = 1.0f - b1 - b2;
    } else {
        const float su = std::sqrt(u1);
        b0 = 1.0f - su;
        b1 = u2 * su;
    }
    const float b2 = 1.0f - b0 - b1;
    const glm::vec3 q = b0 * a + b1 * b + b2 * c;
    const glm::vec3 d = q - p;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0.0f)) return false;
    const float dist = std::sqrt(dist2);
    s.wi = d / dist;
    float cos_l = -glm::dot(n, s.wi) / area2;
    if (cos_l <= 0.0f && !(l.flags & CLP_LIGHTF_TWO_SIDED)) return false;
    cos_l = std::fabs(cos_l);
    if (cos_l <= 0.0f) return false;
    s.pdf = omega > 0.0f ? 1.0f / omega : dist2 / (0.5f * area2 * cos_l);
    s.L = vec3_of(l.L);
    const glm::vec3 err = gamma_bound(10) * (glm::abs(b0 * a) + glm::abs(b1 * b) + glm::abs(b2 * c));
    s.to = offset_ray_origin(q, err, n / area2, -s.wi);
    return true;
}

inline float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Light kinds other than triangles, points, spots and directional lights are
// refused before rendering (bench/embree_path_tracer.cpp): they return false.
inline bool sample_light(const Light* lights, const AliasEntry* alias, std::uint32_t count, glm::vec3 p, float u0,
                         float u1, float u2, LightSample& s) {
    const std::uint32_t li = pick_light(alias, count, u0);
    const Light& l = lights[li];
    const float pmf = alias[li].pmf;
    s.infinite = false;
    s.delta = false;
    switch (l.type) {
    case CLP_LIGHT_TRIANGLE:
        if (!sample_triangle_light(l, p, u1, u2, s)) return false;
        s.pdf *= pmf;
        return true;
    case CLP_LIGHT_POINT:
    case CLP_LIGHT_SPOT: {
        const glm::vec3 d = vec3_of(l.a) - p;
        const float dist2 = glm::dot(d, d);
        if (!(dist2 > 0.0f)) return false;
        s.wi = d * (1.0f / std::sqrt(dist2));
        float falloff = 1.0f;
        if (l.type == CLP_LIGHT_SPOT) falloff = smoothstep(l.cos_outer, l.cos_inner, glm::dot(-s.wi, vec3_of(l.b)));
        s.L = vec3_of(l.L) * (falloff / dist2);
        s.pdf = pmf;
        s.to = vec3_of(l.a);
        s.delta = true;
        return falloff > 0.0f;
    }
    case CLP_LIGHT_DIRECTIONAL:
        s.wi = -vec3_of(l.b);
        s.L = vec3_of(l.L);
        s.pdf = pmf;
        s.infinite = true;
        s.delta = true;
        return true;
    default: return false;
    }
}

inline float power_heuristic(float pdf_a, float pdf_b) {
    if (!(pdf_a > 0.0f)) return 0.0f;
    const float r = pdf_b / pdf_a;
    return 1.0f / (1.0f + r * r);
}

}  // namespace clpath::cpu
