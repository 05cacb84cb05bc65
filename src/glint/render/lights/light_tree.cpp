#include "glint/render/lights/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <ostream>

#include "glint/core/ray.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

double safeSqrt(double x) { return std::sqrt(std::max(x, 0.0)); }
double safeAcos(double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }

/// `v` turned by `angle` about the unit axis `k` (Rodrigues' formula).
Vec3 rotate(const Vec3& v, const Vec3& k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

struct Cone {
    Vec3 w;
    double cosTheta;
};

/// The smallest cone (of this construction) holding both cones (pbrt-v4's DirectionCone Union).
Cone unite(const Cone& a, const Cone& b) {
    if (a.cosTheta <= -1 || b.cosTheta <= -1) return {a.w, -1};
    if (a.w == b.w) return {a.w, std::min(a.cosTheta, b.cosTheta)};  // coplanar emitters
    const double thetaA = safeAcos(a.cosTheta), thetaB = safeAcos(b.cosTheta);
    const double thetaD = safeAcos(dot(a.w, b.w));
    if (std::min(thetaD + thetaB, kPi) <= thetaA) return a;
    if (std::min(thetaD + thetaA, kPi) <= thetaB) return b;
    const double thetaO = (thetaA + thetaD + thetaB) / 2;
    if (thetaO >= kPi) return {a.w, -1};
    const Vec3 axis = cross(a.w, b.w);
    const double len = length(axis);
    if (!(len > 0)) return {a.w, -1};  // opposite axes
    return {normalize(rotate(a.w, axis / len, thetaO - thetaA)), std::cos(thetaO)};
}

double surfaceMeasure(const LightBounds& b) {
    const Vec3 d = b.hi - b.lo;
    const double area = 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    return area > 0 ? area : dot(d, d);  // flat or a point: its diagonal stands in
}

/// pbrt-v4's cost of a group of lights in a split: power times the solid angle its emission
/// may reach (M_omega), times its bounds' area, times how thin the node is along the split's
/// axis (Kr: splits across thin nodes are discouraged).
double splitCost(const LightBounds& b, double kr) {
    // Lambertian emitters (theta_e pi/2) about every normal, or about one: M_omega is 4 pi or
    // pi, without the trigonometry (most nodes of a large mesh light are one or the other).
    if (b.cosThetaE == 0 && (b.cosThetaO <= -1 || b.cosThetaO >= 1))
        return b.phi * (b.cosThetaO <= -1 ? 4 * kPi : kPi) * kr * surfaceMeasure(b);
    const double thetaO = safeAcos(b.cosThetaO), thetaE = safeAcos(b.cosThetaE);
    const double thetaW = std::min(thetaO + thetaE, kPi);
    const double sinO = safeSqrt(1 - b.cosThetaO * b.cosThetaO);
    const double mOmega =
        2 * kPi * (1 - b.cosThetaO) +
        kPi / 2 *
            (2 * thetaW * sinO - std::cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + b.cosThetaO);
    return b.phi * mOmega * kr * surfaceMeasure(b);
}

Vec3 centroid(const LightBounds& b) { return (b.lo + b.hi) * 0.5; }

/// Deeper than this, subtrees are split in half by count, so that no path from the root is
/// longer than 63 steps (a light's path is 64 bits) for up to 2^32 lights.
constexpr int kMaxSahDepth = 30;

}  // namespace

LightBounds LightBounds::point(const Vec3& p, double phi) {
    LightBounds b;
    b.lo = b.hi = p;
    b.phi = phi;
    b.cosThetaO = -1;
    b.cosThetaE = 0;
    return b;
}

LightBounds LightBounds::surface(const Vec3& lo, const Vec3& hi, double phi, const Vec3& n,
                                 bool twoSided) {
    LightBounds b;
    b.lo = lo;
    b.hi = hi;
    b.phi = phi;
    const double len = length(n);
    if (len > 0) {
        b.w = n / len;
        b.cosThetaO = 1;
    } else {
        b.cosThetaO = -1;
    }
    b.cosThetaE = 0;
    b.twoSided = twoSided;
    return b;
}

double LightBounds::importance(const Vec3& p, const Vec3& n) const {
    return LightTree::Compact(*this).importance(p, n);
}

LightTree::Compact::Compact(const LightBounds& b)
    : center(centroid(b)),
      w(b.w),
      radius(static_cast<float>(length(b.hi - b.lo) / 2)),
      phi(static_cast<float>(b.phi)),
      cosThetaO(static_cast<float>(b.cosThetaO)),
      sinThetaO(static_cast<float>(safeSqrt(1 - b.cosThetaO * b.cosThetaO))),
      cosThetaE(static_cast<float>(b.cosThetaE)),
      twoSided(b.twoSided) {}

namespace {

float sqrtf0(float x) { return std::sqrt(std::max(x, 0.0f)); }
float cosSubClampedF(float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 1 : cosA * cosB + sinA * sinB;
}
float sinSubClampedF(float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 0 : sinA * cosB - cosA * sinB;
}

}  // namespace

double LightTree::Compact::importance(const Vec3& pd, const Vec3& nd) const {
    const Vec3f toP = Vec3f(pd) - center;
    const float dist2 = dot(toP, toP);
    // Within the bounds the distance tells nothing: pbrt's floor of half the diagonal.
    const float d2 = std::max(dist2, radius);
    if (!(dist2 > 0)) return phi / std::max(static_cast<double>(d2), 1e-30);
    const float dist = std::sqrt(dist2);
    const Vec3f wi = toP * (1 / dist);
    // The angle the bounds subtend from p, about wi.
    const bool inside = dist2 < radius * radius;
    const float sinB = inside ? 0 : radius / dist;
    const float cosB = inside ? -1 : sqrtf0(1 - sinB * sinB);
    // The smallest angle between an emission normal and a direction to p.
    float cosW = dot(w, wi);
    if (twoSided) cosW = std::abs(cosW);
    const float sinW = sqrtf0(1 - cosW * cosW);
    const float cosX = cosSubClampedF(sinW, cosW, sinThetaO, cosThetaO);
    const float sinX = sinSubClampedF(sinW, cosW, sinThetaO, cosThetaO);
    const float cosP = cosSubClampedF(sinX, cosX, sinB, cosB);
    if (cosP <= cosThetaE) return 0;
    float cosines = cosP;
    if (!(nd == Vec3(0))) {  // the receiving cosine, at best over the bounds
        const float cosI = std::abs(dot(wi, Vec3f(nd)));
        const float sinI = sqrtf0(1 - cosI * cosI);
        cosines *= cosSubClampedF(sinI, cosI, sinB, cosB);
    }
    // In double: a bright point light a hair away must not overflow a float.
    return std::max(static_cast<double>(phi) * cosines / d2, 0.0);
}

std::ostream& operator<<(std::ostream& out, const LightBounds& b) {
    out << "LightBounds{[" << b.lo << " .. " << b.hi << "], phi " << b.phi
        << ", normals within acos(" << b.cosThetaO << ") of " << b.w << ", emitting within acos("
        << b.cosThetaE << ")";
    if (b.twoSided) out << ", two-sided";
    return out << "}";
}

LightBounds unite(const LightBounds& a, const LightBounds& b) {
    if (!(a.phi > 0)) return b;
    if (!(b.phi > 0)) return a;
    LightBounds u;
    u.lo = min(a.lo, b.lo);
    u.hi = max(a.hi, b.hi);
    u.phi = a.phi + b.phi;
    const Cone c = unite(Cone{a.w, a.cosThetaO}, Cone{b.w, b.cosThetaO});
    u.w = c.w;
    u.cosThetaO = c.cosTheta;
    u.cosThetaE = std::min(a.cosThetaE, b.cosThetaE);
    u.twoSided = a.twoSided || b.twoSided;
    return u;
}

LightTree::LightTree(const std::vector<LightBounds>& lights) {
    if (lights.empty()) return;
    std::vector<uint32_t> order(lights.size());
    std::vector<Vec3> centroids(lights.size());
    for (uint32_t i = 0; i < order.size(); ++i) {
        order[i] = i;
        centroids[i] = centroid(lights[i]);
    }
    trail_.assign(lights.size(), 0);
    nodes_.reserve(2 * lights.size() - 1);
    LightBounds all;
    build(lights, centroids, order, 0, order.size(), 0, 0, all);
}

namespace {

/// The split search's cost grows with the lights it weighs (a union of bounds and cones per
/// light, bucket and axis): it weighs all three axes for trees of at most this many lights;
/// in larger trees only the axis of the widest spread of centroids, and only in nodes of at
/// most kSahNode lights, above which the node is halved at the median centroid on that axis
/// (a million emissive triangles: about 1.6 s to build rather than 4.8).
constexpr size_t kFullSahLights = 16384, kSahNode = 256;
constexpr int kBuckets = 12;

}  // namespace

uint32_t LightTree::build(const std::vector<LightBounds>& lights,
                          const std::vector<Vec3>& centroids, std::vector<uint32_t>& order,
                          size_t begin, size_t end, int depth, uint64_t trail,
                          LightBounds& bounds) {
    const uint32_t index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({});
    if (end - begin == 1) {
        bounds = lights[order[begin]];
        nodes_[index] = {Compact(bounds), order[begin], true};
        trail_[order[begin]] = trail;
        return index;
    }
    // The node's box and its centroids' box (the cones and power come from the children).
    Vec3 lo(kInfinity), hi(-kInfinity), cLo(kInfinity), cHi(-kInfinity);
    for (size_t i = begin; i < end; ++i) {
        lo = min(lo, lights[order[i]].lo);
        hi = max(hi, lights[order[i]].hi);
        cLo = min(cLo, centroids[order[i]]);
        cHi = max(cHi, centroids[order[i]]);
    }
    const Vec3 spread = cHi - cLo;
    const int widest = spread.x >= spread.y && spread.x >= spread.z ? 0
                       : spread.y >= spread.z                       ? 1
                                                                    : 2;
    const auto first = order.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = order.begin() + static_cast<std::ptrdiff_t>(end);

    size_t mid = begin + (end - begin) / 2;
    const bool fullSah = lights.size() <= kFullSahLights;
    if (depth < kMaxSahDepth && (fullSah || end - begin <= kSahNode)) {
        // The split of least cost among 12 buckets of centroids along the axes weighed.
        double best = kInfinity;
        int bestDim = -1, bestSplit = 0;
        const Vec3 extent = hi - lo;
        const double maxExtent = std::max({extent.x, extent.y, extent.z});
        for (int dim = fullSah ? 0 : widest; dim < (fullSah ? 3 : widest + 1); ++dim) {
            const double cLoDim = cLo[dim], span = spread[dim];
            if (!(span > 0) || !(extent[dim] > 0)) continue;
            auto bucketOf = [&](uint32_t light) {
                return std::min(
                    static_cast<int>((centroids[light][dim] - cLoDim) / span * kBuckets),
                    kBuckets - 1);
            };
            std::array<LightBounds, kBuckets> buckets{};
            for (size_t i = begin; i < end; ++i) {
                LightBounds& b = buckets[static_cast<size_t>(bucketOf(order[i]))];
                b = unite(b, lights[order[i]]);
            }
            const double kr = maxExtent / extent[dim];
            // The buckets below and above each split, accumulated from either end.
            std::array<LightBounds, kBuckets> below{}, above{};
            below[0] = buckets[0];
            for (int k = 1; k < kBuckets; ++k) below[k] = unite(below[k - 1], buckets[k]);
            above[kBuckets - 1] = buckets[kBuckets - 1];
            for (int k = kBuckets - 2; k >= 0; --k) above[k] = unite(buckets[k], above[k + 1]);
            for (int split = 1; split < kBuckets; ++split) {
                const LightBounds& l = below[split - 1];
                const LightBounds& h = above[split];
                if (!(l.phi > 0) || !(h.phi > 0)) continue;
                const double cost = splitCost(l, kr) + splitCost(h, kr);
                if (cost < best) {
                    best = cost;
                    bestDim = dim;
                    bestSplit = split;
                }
            }
        }
        if (bestDim >= 0) {
            const double cLoDim = cLo[bestDim], span = spread[bestDim];
            auto firstHalf = [&](uint32_t light) {
                const double c = centroids[light][bestDim];
                return std::min(static_cast<int>((c - cLoDim) / span * kBuckets), kBuckets - 1) <
                       bestSplit;
            };
            mid = static_cast<size_t>(std::partition(first, last, firstHalf) - order.begin());
            if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
        }
    } else {
        // Halved at the median centroid on the widest axis (by index where they tie).
        std::nth_element(first, order.begin() + static_cast<std::ptrdiff_t>(mid), last,
                         [&](uint32_t a, uint32_t b) {
                             const double ca = centroids[a][widest], cb = centroids[b][widest];
                             return ca < cb || (ca == cb && a < b);
                         });
    }
    LightBounds below, above;
    build(lights, centroids, order, begin, mid, depth + 1, trail, below);
    const uint32_t second =
        build(lights, centroids, order, mid, end, depth + 1, trail | (1ull << depth), above);
    bounds = unite(below, above);
    nodes_[index] = {Compact(bounds), second, false};
    return index;
}

std::optional<LightTree::Choice> LightTree::sample(const Vec3& p, const Vec3& n, double u) const {
    if (nodes_.empty()) return std::nullopt;
    uint32_t index = 0;
    double probability = 1;
    for (;;) {
        const Node& node = nodes_[index];
        if (node.leaf) {
            if (index > 0 || node.bounds.importance(p, n) > 0)
                return Choice{node.secondOrLight, probability};
            return std::nullopt;
        }
        const double a = nodes_[index + 1].bounds.importance(p, n);
        const double b = nodes_[node.secondOrLight].bounds.importance(p, n);
        if (!(a + b > 0)) return std::nullopt;
        const double pa = a / (a + b);
        if (u < pa) {
            u = std::min(u / pa, 0x1.fffffffffffffp-1);
            probability *= pa;
            index = index + 1;
        } else {
            u = std::min((u - pa) / (1 - pa), 0x1.fffffffffffffp-1);
            probability *= 1 - pa;
            index = node.secondOrLight;
        }
    }
}

double LightTree::pmf(const Vec3& p, const Vec3& n, uint32_t light) const {
    if (light >= trail_.size()) return 0;
    uint64_t trail = trail_[light];
    uint32_t index = 0;
    double probability = 1;
    for (;;) {
        const Node& node = nodes_[index];
        if (node.leaf)
            return node.secondOrLight == light && (index > 0 || node.bounds.importance(p, n) > 0)
                       ? probability
                       : 0;
        const double a = nodes_[index + 1].bounds.importance(p, n);
        const double b = nodes_[node.secondOrLight].bounds.importance(p, n);
        if (!(a + b > 0)) return 0;
        const bool second = trail & 1;
        probability *= (second ? b : a) / (a + b);
        index = second ? node.secondOrLight : index + 1;
        trail >>= 1;
    }
}

}  // namespace glint
