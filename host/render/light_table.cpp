#include "render/light_table.hpp"

#include <cmath>

#include "util/error.hpp"

namespace clpath {
double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

std::vector<AliasEntry> build_alias_table(const std::vector<double>& w) {
    const std::size_t n = w.size();
    double total = 0;
    for (double x : w) total += x;
    if (n == 0 || !(total > 0)) throw Error("internal: alias table needs a positive total weight");
    std::vector<AliasEntry> t(n);
    std::vector<double> scaled(n);
    std::vector<std::size_t> small, large;
    for (std::size_t i = 0; i < n; ++i) {
        t[i].pmf = float(w[i] / total);
        t[i].alias = std::uint32_t(i);
        t[i].pad = 0;
        scaled[i] = w[i] / total * double(n);
        (scaled[i] < 1.0 ? small : large).push_back(i);
    }
    while (!small.empty() && !large.empty()) {
        const std::size_t s = small.back(), l = large.back();
        small.pop_back();
        t[s].prob = float(scaled[s]);
        t[s].alias = std::uint32_t(l);
        scaled[l] -= 1.0 - scaled[s];
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // What is left is 1 up to rounding.
    for (auto i : large) t[i].prob = 1.0f;
    for (auto i : small) t[i].prob = 1.0f;
    return t;
}

LightTable build_light_table(const Scene& scene, const KernelFeatures& f, const EnvironmentMap& env,
                             float scene_radius) {
    LightTable t;
    t.light_of_triangle.assign(scene.triangle_count(), CLP_NO_LIGHT);
    std::vector<double> power;
    if (f.triangle_lights) {
        for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
            const SceneMaterial& m = scene.materials[scene.triangle_material[i]];
            if (!emits(m)) continue;
            // An emission texture or a cut-out varies the emitted light across the
            // triangle: such emitters are found by BSDF sampling alone (unbiased),
            // never light-sampled with the material's constant emission.
            if (m.texture[CLP_TEX_EMISSION] != CLP_NO_TEXTURE || m.alpha_mode != CLP_ALPHA_OPAQUE) continue;
            const glm::vec3 le = load3(m.emission);
            const glm::vec3 a = scene.vertices[3 * i], b = scene.vertices[3 * i + 1], c = scene.vertices[3 * i + 2];
            const double area = 0.5 * glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)));
            if (!(area > 0)) continue;  // cannot be hit or sampled
            Light l{};
            l.type = CLP_LIGHT_TRIANGLE;
            store3(l.a, a);
            store3(l.b, b);
            store3(l.c, c);
            store3(l.L, le);
            const bool two_sided = (m.flags & CLP_MATF_TWO_SIDED_EMISSION) != 0;
            l.flags = two_sided ? CLP_LIGHTF_TWO_SIDED : 0u;
            t.light_of_triangle[i] = std::uint32_t(t.lights.size());
            t.lights.push_back(l);
            // A coloured light of zero luminance still has to be picked sometimes.
            power.push_back(std::max(luminance(le), 1e-6 * double(le.x + le.y + le.z)) * area * M_PI *
                            (two_sided ? 2.0 : 1.0));
        }
    }
    const double disk = M_PI * double(scene_radius) * double(scene_radius);
    if (f.delta_lights) {
        for (const auto& p : scene.lights) {
            Light l{};
            store3(l.L, p.intensity);
            const double lum = std::max(luminance(p.intensity), 1e-6 * double(p.intensity.x + p.intensity.y + p.intensity.z));
            switch (p.type) {
            case PunctualLight::Type::Point:
                l.type = CLP_LIGHT_POINT;
                store3(l.a, p.position);
                power.push_back(4 * M_PI * lum);
                break;
            case PunctualLight::Type::Spot: {
                l.type = CLP_LIGHT_SPOT;
                store3(l.a, p.position);
                store3(l.b, glm::normalize(p.direction));
                l.cos_inner = std::cos(glm::radians(p.spot_inner_degrees));
                l.cos_outer = std::cos(glm::radians(p.spot_outer_degrees));
                // pbrt-v4's estimate of a smooth-falloff spot's flux.
                power.push_back(2 * M_PI * lum * (1 - 0.5 * (l.cos_inner + l.cos_outer)));
                break;
            }
            case PunctualLight::Type::Directional:
                l.type = CLP_LIGHT_DIRECTIONAL;
                store3(l.b, glm::normalize(p.direction));
                power.push_back(disk * lum);
                break;
            }
            t.lights.push_back(l);
        }
    }
    if (f.environment && f.integrator == CLP_INTEGRATOR_PATH && env.average_radiance > 0) {
        Light l{};
        l.type = CLP_LIGHT_ENVIRONMENT;
        t.environment = std::uint32_t(t.lights.size());
        t.lights.push_back(l);
        power.push_back(4 * M_PI * disk * env.average_radiance);
    }
    for (double& p : power)
        if (!std::isfinite(p)) throw Error("a light's power is not finite (emission, intensity or scene too large)");
    double total = 0;
    for (double p : power) total += p;
    if (!(total > 0)) return LightTable{{}, {}, std::vector<std::uint32_t>(scene.triangle_count(), CLP_NO_LIGHT)};
    t.alias = build_alias_table(power);
    return t;
}

}  // namespace clpath
