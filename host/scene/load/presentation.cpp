#include "scene/load/presentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "util/error.hpp"

namespace clpath {
namespace {

struct Bounds {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    glm::vec3 centre() const { return (lo + hi) * 0.5f; }
    float radius() const { return std::max(0.5f * glm::length(hi - lo), 1e-6f); }
};

Bounds bounds_of(const Scene& s) {
    Bounds b;
    for (const auto& v : s.vertices) {
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

// The eye distance at which every corner of the box lies inside the frame,
// with a margin, for a camera looking along -d at the box's centre.
float framing_distance(const Bounds& b, glm::vec3 d, float vfov_deg, float aspect) {
    const glm::vec3 f = -d;
    const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
    const glm::vec3 u = glm::cross(r, f);
    const float margin = 0.8f;  // the box fills at most 80 % of the frame: room for ground and shadow
    const float tan_v = std::tan(glm::radians(vfov_deg) * 0.5f) * margin, tan_h = tan_v * aspect;
    const glm::vec3 c0 = b.centre();
    float dist = 0;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
        const glm::vec3 c = corner - c0;
        // The corner's depth in front of the eye is dist - dot(c, d).
        dist = std::max(dist, std::abs(glm::dot(c, r)) / tan_h + glm::dot(c, d));
        dist = std::max(dist, std::abs(glm::dot(c, u)) / tan_v + glm::dot(c, d));
    }
    return std::max(dist, 1.05f * b.radius());
}

}  // namespace

glm::vec3 presentation_view_direction(const Scene& s) {
    // The triangles' area-weighted normals, at most ~200k of them: the score
    // is a sum, and a regular subsample of a big mesh estimates it well.
    // A triangle listed more than once (a face written twice, or a polygon
    // that goes round its corners again and again, as in assimp's
    // box_longline.obj) counts once: else one face outweighs the rest and
    // the view turns face-on to it.
    std::vector<std::array<float, 9>> tris;
    const std::size_t n = s.triangle_count();
    const std::size_t stride = std::max<std::size_t>(1, n / 200000);
    for (std::size_t t = 0; t < n; t += stride) {
        std::array<glm::vec3, 3> c{s.vertices[3 * t], s.vertices[3 * t + 1], s.vertices[3 * t + 2]};
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
    for (float el : {15.0f, 25.0f, 35.0f, 45.0f})
        for (float az = 0; az < 360; az += 15) {
            const glm::vec3 d = from_angles(az, el);
            double visible = 0;
            for (const auto& v : an) visible += std::max(0.0f, glm::dot(v, d));
            scored.push_back({d, visible});
            best_score = std::max(best_score, visible);
        }
    // Near-ties (within 3 %) go to the view closest to the front-right
    // three-quarter view a photographer would start from.
    const glm::vec3 preferred = from_angles(35, 25);
    double best_pref = -2;
    for (const auto& [d, visible] : scored)
        if (visible >= 0.97 * best_score && glm::dot(d, preferred) > best_pref) {
            best_pref = glm::dot(d, preferred);
            best = d;
        }
    return best;
}

void present_bare_mesh(Scene& s, const PresentationOptions& o) { present_model(s, o, false); }

void present_model(Scene& s, const PresentationOptions& o, bool keep_camera) {
    namespace p = presentation;
    if (s.triangle_count() == 0) throw Error("internal: present_model on an empty scene");
    bool self_lit = !s.lights.empty();
    for (auto m : s.triangle_material) self_lit = self_lit || emits(s.materials[m]);

    const Bounds b = bounds_of(s);
    Camera& cam = s.camera;
    glm::vec3 d;  // towards the camera, for the sun's placement
    if (keep_camera) {
        d = cam.eye - cam.target;
        d = glm::length(glm::vec2(d.x, d.z)) > 0 ? glm::normalize(d) : glm::vec3(0, 0, 1);
    } else {
        d = presentation_view_direction(s);
        cam.width = 640;
        cam.height = 480;
        cam.vfov_degrees = p::kVerticalFov;
        cam.up = glm::vec3(0, 1, 0);
        cam.target = b.centre();
        cam.eye = b.centre() + d * framing_distance(b, d, cam.vfov_degrees, float(cam.width) / float(cam.height));
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
