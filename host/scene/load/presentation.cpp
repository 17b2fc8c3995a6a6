#include "scene/load/presentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "util/error.hpp"

namespace clpath {
namespace {

struct Bounds {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    glm::vec3 centre() const { return (lo + hi) * 0.5f; }
    float radius() const { return std::max(0.5f * glm::length(hi - lo), 1e-6f); }
};

Bounds bounds_of(const std::vector<glm::vec3>& vertices) {
    Bounds b;
    for (const auto& v : vertices) {
        b.lo = glm::min(b.lo, v);
        b.hi = glm::max(b.hi, v);
    }
    return b;
}

glm::vec3 from_angles(float azimuth_deg, float elevation_deg) {
    const float az = glm::radians(azimuth_deg), el = glm::radians(elevation_deg);
    // Azimuth 0 looks from +z (where OBJ models usually face), 90 from +x.
    return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

// The model's bounding sphere about c: the farthest vertex's distance (a
// tighter sphere than the box's, so a round model is not framed small).
float bounding_radius(const std::vector<glm::vec3>& vertices, glm::vec3 c) {
    float r2 = 0;
    for (const auto& v : vertices) {
        const float d2 = glm::dot(v - c, v - c);
        if (std::isfinite(d2)) r2 = std::max(r2, d2);
    }
    return std::max(std::sqrt(r2), 1e-6f);
}

// The eye distance at which a sphere of radius r fills the frame's shorter
// side up to a margin: its silhouette's half-angle asin(r / distance) equals
// the half-field of view whose tangent is margin * tan(fov / 2).
float framing_distance(float r, float vfov_deg, float aspect) {
    const float tan_half = std::tan(glm::radians(vfov_deg) * 0.5f) * std::min(1.0f, aspect);
    return r / std::sin(std::atan(presentation::kFramingMargin * tan_half));
}

std::string percent(float fraction) {
    char buf[32];
    std::snprintf(buf, sizeof buf, fraction < 0.1f ? "%.2g %%" : "%.0f %%", double(fraction) * 100.0);
    return buf;
}

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// A texture's linear RGB at uv (nearest texel, repeat): enough for an estimate
// of how much light a textured emitter gives.
glm::vec3 texel_at(const Texture& t, glm::vec2 uv) {
    if (t.width <= 0 || t.height <= 0) return glm::vec3(1);
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    const std::size_t x = std::min<std::size_t>(std::size_t(u * float(t.width)), std::size_t(t.width - 1));
    const std::size_t y = std::min<std::size_t>(std::size_t(v * float(t.height)), std::size_t(t.height - 1));
    const std::size_t i = 4 * (y * std::size_t(t.width) + x);
    if (t.is_float) return t.rgba32.size() >= i + 3 ? glm::vec3(t.rgba32[i], t.rgba32[i + 1], t.rgba32[i + 2]) : glm::vec3(1);
    if (t.rgba8.size() < i + 3) return glm::vec3(1);
    auto decode = [](std::uint8_t b) {  // the sRGB transfer function (IEC 61966-2-1)
        const float c = float(b) / 255.0f;
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    return {decode(t.rgba8[i]), decode(t.rgba8[i + 1]), decode(t.rgba8[i + 2])};
}

// The irradiance (luminance, W/m^2) the scene's own emitters and punctual
// lights bring to a model of bounding sphere (c, r): a point or spot light of
// intensity I at distance d gives I / d^2 (d at least r); a directional light
// its irradiance; emitting triangles their power (pi * radiance * area, a
// Lambertian emitter's) spread over a sphere of radius r around the model,
// which is what they give it on average. An emissive texture is read at each
// triangle's centroid, so a texture that is black but for a small display
// counts as the display.
float own_irradiance(const Scene& s, glm::vec3 c, float r) {
    double power = 0;
    const bool have_uvs = s.uvs.size() == s.vertices.size();
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        const SceneMaterial& m = s.materials[s.triangle_material[t]];
        if (!emits(m)) continue;
        glm::vec3 e = load3(m.emission);
        const int tex = m.texture[CLP_TEX_EMISSION];
        if (tex >= 0 && std::size_t(tex) < s.textures.size() && have_uvs)
            e *= texel_at(s.textures[std::size_t(tex)], (s.uvs[3 * t] + s.uvs[3 * t + 1] + s.uvs[3 * t + 2]) / 3.0f);
        const glm::vec3 a = s.vertices[3 * t], b = s.vertices[3 * t + 1], d = s.vertices[3 * t + 2];
        const double area = 0.5 * double(glm::length(glm::cross(b - a, d - a)));
        if (std::isfinite(area)) power += M_PI * double(luminance(e)) * area;
    }
    double e = power / (4.0 * M_PI * double(r) * double(r));
    for (const auto& l : s.lights) {
        if (l.type == PunctualLight::Type::Directional) {
            e += luminance(l.intensity);
        } else {
            const float dist = std::max(glm::length(l.position - c), r);
            e += luminance(l.intensity) / (dist * dist);
        }
    }
    return float(e);
}

}  // namespace

float presentation_irradiance() {
    // The sun's irradiance plus a constant sky's on a horizontal surface (pi L).
    return luminance(presentation::kSunIrradiance) + float(M_PI) * luminance(presentation::kSkyRadiance);
}

namespace {

// The triangles the scene places, three vertices each: its own, then every
// instance's copies (corners swapped back where the map mirrors, so the
// winding still faces out), each mesh's triangles subsampled evenly when all
// of them would pass kMaxPlaced, so that 10,000 copies of a mesh cost what
// 2 million triangles cost.
std::vector<glm::vec3> placed_triangles(const Scene& s) {
    constexpr std::size_t kMaxPlaced = 2'000'000;
    if (s.instances.empty()) return s.vertices;
    std::vector<glm::vec3> out = s.vertices;
    const std::size_t placed = s.placed_triangle_count() - s.triangle_count();
    const std::size_t stride = std::max<std::size_t>(1, (placed + kMaxPlaced - 1) / kMaxPlaced);
    for (const auto& in : s.instances) {
        const auto& v = s.meshes[in.mesh].vertices;
        const bool flip = glm::determinant(glm::mat3(in.object_to_world)) < 0;
        for (std::size_t t = 0; t < v.size() / 3; t += stride)
            for (int c : {0, flip ? 2 : 1, flip ? 1 : 2})
                out.push_back(glm::vec3(in.object_to_world * glm::vec4(v[3 * t + std::size_t(c)], 1.0f)));
    }
    return out;
}

glm::vec3 view_direction(const std::vector<glm::vec3>& vertices) {
    // The triangles' area-weighted normals, at most ~200k of them: the score
    // is a sum, and a regular subsample of a big mesh estimates it well.
    // A triangle listed more than once (a face written twice, or a polygon
    // that goes round its corners again and again, as in assimp's
    // box_longline.obj) counts once: else one face outweighs the rest and
    // the view turns face-on to it.
    std::vector<std::array<float, 9>> tris;
    const std::size_t n = vertices.size() / 3;
    const std::size_t stride = std::max<std::size_t>(1, n / 200000);
    for (std::size_t t = 0; t < n; t += stride) {
        std::array<glm::vec3, 3> c{vertices[3 * t], vertices[3 * t + 1], vertices[3 * t + 2]};
        // (A non-finite corner would also break the sort's ordering.)
        if (!std::isfinite(c[0].x + c[0].y + c[0].z + c[1].x + c[1].y + c[1].z + c[2].x + c[2].y + c[2].z)) continue;
        // The same triangle from any starting corner, its winding (facing) kept.
        auto less = [](glm::vec3 p, glm::vec3 q) { return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z); };
        const std::size_t first = less(c[1], c[0]) ? (less(c[2], c[1]) ? 2 : 1) : (less(c[2], c[0]) ? 2 : 0);
        std::rotate(c.begin(), c.begin() + first, c.end());
        tris.push_back({c[0].x, c[0].y, c[0].z, c[1].x, c[1].y, c[1].z, c[2].x, c[2].y, c[2].z});
    }
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
    std::vector<glm::vec3> an;  // normal * area
    for (const auto& t : tris) {
        const glm::vec3 a(t[0], t[1], t[2]), b(t[3], t[4], t[5]), c(t[6], t[7], t[8]);
        const glm::vec3 cr = 0.5f * glm::cross(b - a, c - a);
        if (std::isfinite(cr.x + cr.y + cr.z)) an.push_back(cr);  // finite corners can still overflow
    }
    glm::vec3 best(0, 0, 1);
    double best_score = -1;
    std::vector<std::pair<glm::vec3, double>> scored;
    namespace p = presentation;
    for (float el : {p::kMaxElevation / 3, 2 * p::kMaxElevation / 3, p::kMaxElevation})
        for (float az = 0; az < 360; az += 15) {
            const glm::vec3 d = from_angles(az, el);
            double visible = 0;
            for (const auto& v : an) visible += std::max(0.0f, glm::dot(v, d));
            scored.push_back({d, visible});
            best_score = std::max(best_score, visible);
        }
    // Near-ties (within 3 %) go to the view closest to the front-right
    // three-quarter view a photographer would start from.
    const glm::vec3 preferred = from_angles(35, 20);
    double best_pref = -2;
    for (const auto& [d, visible] : scored)
        if (visible >= 0.97 * best_score && glm::dot(d, preferred) > best_pref) {
            best_pref = glm::dot(d, preferred);
            best = d;
        }
    return best;
}

}  // namespace

glm::vec3 presentation_view_direction(const Scene& s) {
    return s.instances.empty() ? view_direction(s.vertices) : view_direction(placed_triangles(s));
}

void present_bare_mesh(Scene& s, const PresentationOptions& o) { present_model(s, o, false); }

void present_model(Scene& s, const PresentationOptions& o, bool keep_camera) {
    namespace p = presentation;
    if (s.placed_triangle_count() == 0) throw Error("internal: present_model on an empty scene");
    bool has_own_light = !s.lights.empty();
    for (auto m : s.triangle_material) has_own_light = has_own_light || emits(s.materials[m]);

    std::vector<glm::vec3> copies;  // only for instances: the flat scene's own vertices are measured in place
    const std::vector<glm::vec3>& placed = s.instances.empty() ? s.vertices : (copies = placed_triangles(s));
    const Bounds b = bounds_of(placed);
    const glm::vec3 centre = b.centre();
    const float radius = bounding_radius(placed, centre);
    // The model's own light decides, not its mere presence: a helmet whose
    // only emitter is a small visor display would otherwise render black.
    const float own = has_own_light ? own_irradiance(s, centre, radius) : 0.0f;
    const float ours = presentation_irradiance();
    const bool self_lit = has_own_light && own >= p::kOwnLightEnough * ours;
    if (o.environment) {
        s.notes.push_back("presentation: the environment given lights the model, with a ground under it");
    } else if (self_lit) {
        s.notes.push_back("presentation: the model's own lights and emitters light it (about " + percent(own / ours) +
                          " of the default sky and sun's irradiance), so no sky, sun or ground is added");
    } else if (has_own_light) {
        s.notes.push_back("presentation: the model's own lights and emitters give about " + percent(own / ours) +
                          " of the default sky and sun's irradiance (under " + percent(p::kOwnLightEnough) +
                          "), so a sky, a sun and a ground are added beside them");
    } else {
        s.notes.push_back("presentation: the model brings no light, so a sky, a sun and a ground are added");
    }
    Camera& cam = s.camera;
    glm::vec3 d;  // towards the camera, for the sun's placement
    if (keep_camera) {
        d = cam.eye - cam.target;
        d = glm::length(glm::vec2(d.x, d.z)) > 0 ? glm::normalize(d) : glm::vec3(0, 0, 1);
    } else {
        d = view_direction(placed);
        cam.width = 640;
        cam.height = 480;
        cam.vfov_degrees = p::kVerticalFov;
        cam.up = glm::vec3(0, 1, 0);
        cam.target = centre;
        cam.eye = centre + d * framing_distance(radius, cam.vfov_degrees, float(cam.width) / float(cam.height));
    }

    if (o.ground && (!self_lit || o.environment)) {
        // A square under the model, a hair below its lowest point so that a
        // flat base does not fight with it for the same depth.
        const float r = b.radius();
        const float y = b.lo.y - 1e-3f * r, h = p::kGroundHalfSize * r;
        const glm::vec3 c = b.centre();
        const glm::vec3 v00(c.x - h, y, c.z - h), v01(c.x - h, y, c.z + h), v11(c.x + h, y, c.z + h),
            v10(c.x + h, y, c.z - h);
        const std::uint32_t ground = s.add_material("(ground)", diffuse(glm::vec3(p::kGroundAlbedo)));
        s.add_triangles({v00, v01, v11, v00, v11, v10}, ground);  // counter-clockwise from above: facing up
        if (!s.normals.empty()) s.normals.insert(s.normals.end(), 6, glm::vec3(0, 1, 0));
    }

    if (o.environment) {
        s.environment = *o.environment;
    } else if (!self_lit) {
        s.environment.color = p::kSkyRadiance;
        PunctualLight sun;
        sun.type = PunctualLight::Type::Directional;
        // The sun stands behind the camera's shoulder, turned aside, so the
        // lit faces show shape and the shadow falls beside the model.
        const float cam_azimuth = glm::degrees(std::atan2(d.x, d.z));
        const glm::vec3 to_sun = from_angles(cam_azimuth + p::kSunAzimuthOffset, p::kSunElevation);
        sun.direction = -to_sun;
        sun.intensity = p::kSunIrradiance;
        s.lights.push_back(sun);
    }
}

}  // namespace clpath
