#include "render/light_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/light_table.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

// Bounds of one light or a set, in double while building.
struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    glm::dvec3 axis{0, 0, 1};
    double power = 0, cos_o = 1, cos_e = 1;
    bool two_sided = false;
    glm::dvec3 centroid() const { return 0.5 * (lo + hi); }
};

double angle_of(double c) { return std::acos(std::clamp(c, -1.0, 1.0)); }

// The smallest cone holding two cones (pbrt-v4's DirectionCone Union).
void union_cone(glm::dvec3 wa, double ca, glm::dvec3 wb, double cb, glm::dvec3* w, double* c) {
    const double ta = angle_of(ca), tb = angle_of(cb), td = angle_of(glm::dot(wa, wb));
    if (std::min(td + tb, M_PI) <= ta) { *w = wa; *c = ca; return; }
    if (std::min(td + ta, M_PI) <= tb) { *w = wb; *c = cb; return; }
    const double to = 0.5 * (ta + td + tb);
    const glm::dvec3 r = glm::cross(wa, wb);
    if (to >= M_PI || glm::dot(r, r) == 0) { *w = wa; *c = -1; return; }
    // Rotate wa towards wb by to - ta about r (Rodrigues).
    const glm::dvec3 k = glm::normalize(r);
    const double t = to - ta;
    *w = glm::normalize(wa * std::cos(t) + glm::cross(k, wa) * std::sin(t) + k * glm::dot(k, wa) * (1 - std::cos(t)));
    *c = std::cos(to);
}

Bounds unite(const Bounds& a, const Bounds& b) {
    if (a.power == 0) return b;
    if (b.power == 0) return a;
    Bounds u;
    u.lo = glm::min(a.lo, b.lo);
    u.hi = glm::max(a.hi, b.hi);
    union_cone(a.axis, a.cos_o, b.axis, b.cos_o, &u.axis, &u.cos_o);
    u.cos_e = std::min(a.cos_e, b.cos_e);
    u.power = a.power + b.power;
    u.two_sided = a.two_sided || b.two_sided;
    return u;
}

// pbrt-v4's BVHLightSampler::EvaluateCost: power x the orientation cone's
// measure M_omega (Conty Estevez and Kulla, eq. 1) x surface area, with Kr
// penalising thin boxes split across their short side.
double split_cost(const Bounds& b, const Bounds& whole, int dim) {
    const double to = angle_of(b.cos_o), te = angle_of(b.cos_e);
    const double tw = std::min(to + te, M_PI), so = std::sin(to);
    const double m_omega = 2 * M_PI * (1 - std::cos(to)) +
                           M_PI / 2 * (2 * tw * so - std::cos(to - 2 * tw) - 2 * to * so + std::cos(to));
    const glm::dvec3 d = whole.hi - whole.lo;
    const double kr = d[dim] > 0 ? std::max(d.x, std::max(d.y, d.z)) / d[dim] : 1.0;
    const glm::dvec3 e = b.hi - b.lo;
    const double area = 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
    return b.power * m_omega * kr * area;
}

std::optional<Bounds> light_bounds(const Light& l) {
    Bounds b;
    const glm::vec3 L = load3(l.L);
    const double lum = std::max(luminance(L), 1e-6 * double(L.x + L.y + L.z));
    const glm::dvec3 a = glm::dvec3(load3(l.a));
    switch (l.type) {
    case CLP_LIGHT_TRIANGLE: {
        const glm::dvec3 v1(load3(l.b)), v2(load3(l.c));
        const glm::dvec3 n = glm::cross(v1 - a, v2 - a);
        const double area = 0.5 * glm::length(n);
        if (!(area > 0)) return std::nullopt;
        b.lo = glm::min(a, glm::min(v1, v2));
        b.hi = glm::max(a, glm::max(v1, v2));
        b.axis = glm::normalize(n);  // emission is along +n (kernels/lights.cl)
        b.cos_o = 1;
        b.cos_e = 0;  // cos(pi/2): a diffuse emitter
        b.two_sided = (l.flags & CLP_LIGHTF_TWO_SIDED) != 0;
        b.power = lum * area * M_PI * (b.two_sided ? 2.0 : 1.0);
        break;
    }
    case CLP_LIGHT_POINT:
        b.lo = b.hi = a;
        b.cos_o = -1;
        b.cos_e = 0;
        b.power = 4 * M_PI * lum;
        break;
    case CLP_LIGHT_SPOT:
        // As pbrt-v4: the cone to the full-intensity edge, widened by the falloff.
        b.lo = b.hi = a;
        b.axis = glm::normalize(glm::dvec3(load3(l.b)));
        b.cos_o = l.cos_inner;
        b.cos_e = std::cos(std::max(0.0, angle_of(l.cos_outer) - angle_of(l.cos_inner)));
        b.power = 4 * M_PI * lum;
        break;
    default: return std::nullopt;  // infinite
    }
    if (!(b.power > 0)) return std::nullopt;
    return b;
}

struct Item {
    std::uint32_t light;
    Bounds b;
};

std::uint32_t encode_octahedral(glm::dvec3 v) {
    v /= std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
    double x = v.x, y = v.y;
    if (v.z < 0) {
        x = (1 - std::abs(v.y)) * (v.x >= 0 ? 1 : -1);
        y = (1 - std::abs(v.x)) * (v.y >= 0 ? 1 : -1);
    }
    auto q = [](double c) { return std::uint32_t(std::lround(std::clamp((c * 0.5 + 0.5) * 65535.0, 0.0, 65535.0))); };
    return q(x) | q(y) << 16;
}

glm::vec3 decode_octahedral(std::uint32_t e) {
    float x = float(e & 0xffffu) / 65535.0f * 2.0f - 1.0f, y = float(e >> 16) / 65535.0f * 2.0f - 1.0f;
    const float z = 1.0f - std::abs(x) - std::abs(y);
    if (z < 0) {
        const float ox = x;
        x = (1.0f - std::abs(y)) * (x >= 0 ? 1.0f : -1.0f);
        y = (1.0f - std::abs(ox)) * (y >= 0 ? 1.0f : -1.0f);
    }
    return glm::normalize(glm::vec3(x, y, z));
}

// Cosines over [-1, 1] in 15 bits, rounded down (a wider cone).
std::uint32_t quantise_cos(double c) {
    return std::uint32_t(std::clamp(std::floor((std::clamp(c, -1.0, 1.0) + 1) * 0.5 * 32767.0), 0.0, 32767.0));
}
float dequantise_cos(std::uint32_t q) { return float(q) / 32767.0f * 2.0f - 1.0f; }

struct Builder {
    LightBvh& bvh;
    glm::dvec3 lo, extent;

    std::uint32_t quantise(double x, int axis, bool upper) const {
        const double s = bvh.scale[axis];
        if (!(s > 0)) return upper ? 65535u : 0u;
        double q = (x - lo[axis]) / extent[axis] * 65535.0;
        q = upper ? std::ceil(q) : std::floor(q);
        auto qi = std::uint32_t(std::clamp(q, 0.0, 65535.0));
        // The float decode must still contain x.
        auto dec = [&](std::uint32_t v) { return bvh.origin[axis] + float(v) * bvh.scale[axis]; };
        if (upper)
            while (qi < 65535u && double(dec(qi)) < x) ++qi;
        else
            while (qi > 0u && double(dec(qi)) > x) --qi;
        return qi;
    }

    LightBvhNode encode(const Bounds& b) const {
        LightBvhNode n{};
        for (int k = 0; k < 3; ++k) n.qbounds[k] = quantise(b.lo[k], k, false) | quantise(b.hi[k], k, true) << 16;
        n.axis = encode_octahedral(b.axis);
        double cos_o = b.cos_o;
        if (cos_o > -1) {
            // Widen the cone by the axis' quantisation error (and a margin for float decoding).
            const double err = angle_of(glm::dot(glm::dvec3(decode_octahedral(n.axis)), b.axis)) + 1e-4;
            cos_o = std::cos(std::min(M_PI, angle_of(cos_o) + err));
        }
        n.power = float(b.power);
        n.cones = quantise_cos(cos_o) | quantise_cos(b.cos_e) << 15 | (b.two_sided ? CLP_LIGHT_BVH_TWO_SIDED : 0u);
        return n;
    }

    Bounds build(std::vector<Item>& items, std::size_t begin, std::size_t end, int depth, std::uint64_t trail) {
        const std::uint32_t index = std::uint32_t(bvh.nodes.size());
        bvh.nodes.emplace_back();
        bvh.depth = std::max(bvh.depth, depth);
        if (end - begin == 1) {
            const Item& it = items[begin];
            LightBvhNode n = encode(it.b);
            n.child = it.light;
            n.flags = CLP_LIGHT_BVH_LEAF;
            bvh.nodes[index] = n;
            bvh.trail[it.light] = trail | std::uint64_t(1) << depth;
            return it.b;
        }
        Bounds whole, centroids;
        for (std::size_t i = begin; i < end; ++i) {
            whole = unite(whole, items[i].b);
            centroids.lo = glm::min(centroids.lo, items[i].b.centroid());
            centroids.hi = glm::max(centroids.hi, items[i].b.centroid());
        }
        std::size_t mid = begin + (end - begin) / 2;
        const glm::dvec3 ce = centroids.hi - centroids.lo;
        // The SAH-like split of pbrt-v4 over 12 buckets a dimension, unless the
        // depth left only allows a balanced one (2^30 lights fit below).
        double best = std::numeric_limits<double>::infinity();
        int best_dim = -1, best_bucket = 0;
        constexpr int kBuckets = 12;
        if (depth < kLightBvhMaxDepth - 32) {
            for (int dim = 0; dim < 3; ++dim) {
                if (!(ce[dim] > 0)) continue;
                Bounds bucket[kBuckets];
                for (std::size_t i = begin; i < end; ++i) {
                    int k = int((items[i].b.centroid()[dim] - centroids.lo[dim]) / ce[dim] * kBuckets);
                    k = std::clamp(k, 0, kBuckets - 1);
                    bucket[k] = unite(bucket[k], items[i].b);
                }
                for (int s = 0; s < kBuckets - 1; ++s) {
                    Bounds below, above;
                    for (int k = 0; k <= s; ++k) below = unite(below, bucket[k]);
                    for (int k = s + 1; k < kBuckets; ++k) above = unite(above, bucket[k]);
                    if (below.power == 0 || above.power == 0) continue;
                    const double c = split_cost(below, whole, dim) + split_cost(above, whole, dim);
                    if (c < best) { best = c; best_dim = dim; best_bucket = s; }
                }
            }
        }
        if (best_dim >= 0) {
            const auto it = std::partition(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end),
                                           [&](const Item& x) {
                                               int k = int((x.b.centroid()[best_dim] - centroids.lo[best_dim]) /
                                                           ce[best_dim] * kBuckets);
                                               return std::clamp(k, 0, kBuckets - 1) <= best_bucket;
                                           });
            mid = std::size_t(it - items.begin());
        }
        if (best_dim < 0 || mid == begin || mid == end) {
            // Coincident centroids, or the depth limit: halve along the widest axis.
            int dim = 0;
            for (int k = 1; k < 3; ++k)
                if (ce[k] > ce[dim]) dim = k;
            mid = begin + (end - begin) / 2;
            std::nth_element(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(mid),
                             items.begin() + std::ptrdiff_t(end), [&](const Item& x, const Item& y) {
                                 return x.b.centroid()[dim] < y.b.centroid()[dim];
                             });
        }
        const Bounds b0 = build(items, begin, mid, depth + 1, trail);
        const std::uint32_t second = std::uint32_t(bvh.nodes.size());
        const Bounds b1 = build(items, mid, end, depth + 1, trail | std::uint64_t(1) << depth);
        const Bounds u = unite(b0, b1);
        LightBvhNode n = encode(u);
        n.child = second;
        n.flags = 0;
        bvh.nodes[index] = n;
        return u;
    }
};

float cos_sub_clamped(float sa, float ca, float sb, float cb) { return ca > cb ? 1.0f : ca * cb + sa * sb; }
float sin_sub_clamped(float sa, float ca, float sb, float cb) { return ca > cb ? 0.0f : sa * cb - ca * sb; }
float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

}  // namespace

LightBvh build_light_bvh(const std::vector<Light>& lights) {
    LightBvh bvh;
    bvh.trail.assign(lights.size(), 0);
    std::vector<Item> items;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type == CLP_LIGHT_DIRECTIONAL || l.type == CLP_LIGHT_ENVIRONMENT) {
            bvh.infinite.push_back(std::uint32_t(i));
            continue;
        }
        if (auto b = light_bounds(l)) items.push_back({std::uint32_t(i), *b});
    }
    if (items.empty()) return bvh;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Item& it : items) {
        if (!std::isfinite(it.b.power)) throw Error("a light's power is not finite (emission, intensity or scene too large)");
        lo = glm::min(lo, it.b.lo);
        hi = glm::max(hi, it.b.hi);
    }
    bvh.origin = glm::vec3(lo);
    // The frame starts at or below lo in float, and its step reaches hi.
    for (int k = 0; k < 3; ++k)
        if (double(bvh.origin[k]) > lo[k]) bvh.origin[k] = std::nextafter(bvh.origin[k], -INFINITY);
    const glm::dvec3 extent = hi - glm::dvec3(bvh.origin);
    for (int k = 0; k < 3; ++k) {
        bvh.scale[k] = float(extent[k] / 65535.0);
        if (extent[k] > 0)
            while (double(bvh.origin[k] + 65535.0f * bvh.scale[k]) < hi[k])
                bvh.scale[k] = std::nextafter(bvh.scale[k], INFINITY);
    }
    Builder b{bvh, glm::dvec3(bvh.origin), extent};
    b.build(items, 0, items.size(), 0, 0);
    return bvh;
}

LightBounds decode_light_bounds(const LightBvh& bvh, const LightBvhNode& n) {
    LightBounds b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = bvh.origin[k] + float(n.qbounds[k] & 0xffffu) * bvh.scale[k];
        b.hi[k] = bvh.origin[k] + float(n.qbounds[k] >> 16) * bvh.scale[k];
    }
    b.axis = decode_octahedral(n.axis);
    b.power = n.power;
    b.cos_theta_o = dequantise_cos(n.cones & 0x7fffu);
    b.cos_theta_e = dequantise_cos((n.cones >> 15) & 0x7fffu);
    b.two_sided = (n.cones & CLP_LIGHT_BVH_TWO_SIDED) != 0;
    return b;
}

float light_bounds_importance(const LightBounds& b, glm::vec3 p, glm::vec3 n) {
    const glm::vec3 pc = 0.5f * (b.lo + b.hi), diag = b.hi - b.lo;
    const glm::vec3 d = p - pc;
    const float dist2 = glm::dot(d, d);
    // As pbrt-v4: no closer than half the box's diagonal, to stay finite inside it.
    const float d2 = std::max(dist2, 0.5f * glm::length(diag));
    const glm::vec3 wi = dist2 > 0 ? d / std::sqrt(dist2) : glm::vec3(0, 0, 1);
    float cos_w = glm::dot(b.axis, wi);
    if (b.two_sided) cos_w = std::abs(cos_w);
    const float sin_w = safe_sqrt(1 - cos_w * cos_w);
    // The directions the box subtends at p: its bounding sphere's cone.
    const float r2 = 0.25f * glm::dot(diag, diag);
    const float cos_b = dist2 < r2 ? -1.0f : safe_sqrt(1 - r2 / dist2);
    const float sin_b = safe_sqrt(1 - cos_b * cos_b);
    const float sin_o = safe_sqrt(1 - b.cos_theta_o * b.cos_theta_o);
    // The angle from the cone to p's direction, less the box's spread, clamped at 0.
    const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, b.cos_theta_o);
    const float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, b.cos_theta_o);
    const float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if (cos_p <= b.cos_theta_e) return 0.0f;
    float importance = b.power * cos_p / d2;
    if (n != glm::vec3(0.0f)) {
        const float cos_i = std::abs(glm::dot(wi, n));
        const float sin_i = safe_sqrt(1 - cos_i * cos_i);
        importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
    }
    return std::max(importance, 0.0f);
}

namespace {
float p_infinite(const LightBvh& bvh) {
    const float ni = float(bvh.infinite.size());
    return ni / (ni + (bvh.nodes.empty() ? 0.0f : 1.0f));
}
float importance_of(const LightBvh& bvh, std::uint32_t node, glm::vec3 p, glm::vec3 n) {
    return light_bounds_importance(decode_light_bounds(bvh, bvh.nodes[node]), p, n);
}
}  // namespace

std::optional<LightPick> sample_light_bvh(const LightBvh& bvh, glm::vec3 p, glm::vec3 n, float u) {
    constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
    const float pi = p_infinite(bvh);
    if (!bvh.infinite.empty()) {
        if (u < pi) {
            const float v = std::min(u / pi, kOneMinusEpsilon);
            const std::size_t k = std::min(std::size_t(v * float(bvh.infinite.size())), bvh.infinite.size() - 1);
            return LightPick{bvh.infinite[k], pi / float(bvh.infinite.size())};
        }
        if (bvh.nodes.empty()) return std::nullopt;
        u = std::min((u - pi) / (1 - pi), kOneMinusEpsilon);
    }
    if (bvh.nodes.empty()) return std::nullopt;
    float pmf = 1 - pi;
    std::uint32_t i = 0;
    while (!(bvh.nodes[i].flags & CLP_LIGHT_BVH_LEAF)) {
        const std::uint32_t c0 = i + 1, c1 = bvh.nodes[i].child;
        const float i0 = importance_of(bvh, c0, p, n), i1 = importance_of(bvh, c1, p, n);
        if (i0 == 0 && i1 == 0) return std::nullopt;
        // The pmf multiplies the same quotients light_bvh_pmf does.
        const float p0 = i0 / (i0 + i1), p1 = i1 / (i0 + i1);
        if (u < p0) {
            pmf *= p0;
            u = std::min(u / p0, kOneMinusEpsilon);
            i = c0;
        } else {
            pmf *= p1;
            u = std::min((u - p0) / (1 - p0), kOneMinusEpsilon);
            i = c1;
        }
    }
    // A lone leaf at the root was never weighed against a sibling.
    if (i == 0 && !(importance_of(bvh, 0, p, n) > 0)) return std::nullopt;
    return LightPick{bvh.nodes[i].child, pmf};
}

float light_bvh_pmf(const LightBvh& bvh, glm::vec3 p, glm::vec3 n, std::uint32_t light) {
    const float pi = p_infinite(bvh);
    if (std::find(bvh.infinite.begin(), bvh.infinite.end(), light) != bvh.infinite.end())
        return pi / float(bvh.infinite.size());
    std::uint64_t trail = light < bvh.trail.size() ? bvh.trail[light] : 0;
    if (trail == 0) return 0.0f;
    float pmf = 1 - pi;
    std::uint32_t i = 0;
    while (!(bvh.nodes[i].flags & CLP_LIGHT_BVH_LEAF)) {
        const std::uint32_t c0 = i + 1, c1 = bvh.nodes[i].child;
        const float i0 = importance_of(bvh, c0, p, n), i1 = importance_of(bvh, c1, p, n);
        if (i0 == 0 && i1 == 0) return 0.0f;
        if (trail & 1) {
            pmf *= i1 / (i0 + i1);
            i = c1;
        } else {
            pmf *= i0 / (i0 + i1);
            i = c0;
        }
        trail >>= 1;
    }
    if (i == 0 && !(importance_of(bvh, 0, p, n) > 0)) return 0.0f;
    return pmf;
}

}  // namespace clpath
