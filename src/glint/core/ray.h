#pragma once
/// Rays p(t) = origin + t * dir, valid for t in (tMin, tMax), and what traversal returns.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <utility>

#include "glint/math/bbox.h"
#include "glint/math/vec3.h"

namespace glint {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A ray in double precision, as the camera and the integrator make them.
struct Ray {
    Vec3 origin;
    Vec3 dir;  ///< Unit length for every ray Glint traces.
    double tMin = 0;
    double tMax = kInfinity;

    constexpr Vec3 at(double t) const { return origin + dir * t; }
};
/// "Ray{origin (x, y, z), dir (x, y, z), t [tMin, tMax]}".
std::ostream& operator<<(std::ostream& out, const Ray& r);

/// The same ray in float for traversal, with what box and triangle tests need precomputed.
struct TraversalRay {
    Vec3f origin, dir;
    /// 1/dir, with components of magnitude below 1e-18 replaced by +-1e18 so that slab
    /// distances are never 0 * infinity.
    Vec3f invDir;
    float tMin = 0, tMax = 0;
    /// The watertight triangle test's frame: kz is the axis of largest |dir|, and the shear
    /// (sx, sy, sz) maps dir to (0, 0, 1) in axes (kx, ky, kz).
    int kx = 0, ky = 1, kz = 2;
    float sx = 0, sy = 0, sz = 1;

    TraversalRay() = default;

    explicit TraversalRay(const Ray& r)
        : TraversalRay(Vec3f(r.origin), Vec3f(r.dir), static_cast<float>(r.tMin),
                       static_cast<float>(r.tMax)) {}

    TraversalRay(const Vec3f& o, const Vec3f& d, float t0, float t1)
        : origin(o), dir(d), tMin(t0), tMax(t1) {
        for (int a = 0; a < 3; ++a) {
            float c = dir[a];
            invDir[a] = std::abs(c) < 1e-18f ? (c < 0 ? -1e18f : 1e18f) : 1 / c;
        }
        Vec3f ad(std::abs(dir.x), std::abs(dir.y), std::abs(dir.z));
        kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
        kx = (kz + 1) % 3;
        ky = (kx + 1) % 3;
        sx = dir[kx] / dir[kz];
        sy = dir[ky] / dir[kz];
        sz = 1 / dir[kz];
    }
};

/// Where `ray` enters box `b` within [ray.tMin, tMax], or +infinity if it misses it there. The
/// far planes are moved out by 4 ulps, as the SIMD kernels move them, so that rounding never
/// loses a box around a surface. Scalar: for the few boxes tested beside the BVH's kernels.
inline float boxEntry(const Bounds3f& b, const TraversalRay& ray, float tMax) {
    float t0 = ray.tMin, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        float n = (b.lo[a] - ray.origin[a]) * ray.invDir[a];
        float f = (b.hi[a] - ray.origin[a]) * ray.invDir[a];
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f * (1 + 4 * std::numeric_limits<float>::epsilon()));
        if (t0 > t1) return std::numeric_limits<float>::infinity();
    }
    return t0;
}

/// The closest hit found by traversal, in float. The shading data is recomputed in double for
/// the winner only (Primitives::interaction).
struct Hit {
    float t = std::numeric_limits<float>::infinity();
    uint32_t primId = 0;  ///< Index into the scene's primitives.
    /// When `primId` is an instance (a placed shared mesh): the mesh's own primitive that was
    /// hit. Meaningless otherwise.
    uint32_t subId = 0;
};
/// "Hit{t 1.5, prim 12}" (with ", sub 3" for an instance's primitive), or "Hit{none}".
std::ostream& operator<<(std::ostream& out, const Hit& h);

/// Whether a candidate hit (t, id) beats `best`: nearer, or as near with a lower id. The tie
/// rule makes the closest hit independent of the order primitives are tested in.
inline bool closerHit(float t, uint32_t id, const Hit& best) {
    return t < best.t || (t == best.t && id < best.primId);
}

/// Up to eight rays traced together (e.g. coherent camera rays), each prepared for traversal.
struct RayPacket8 {
    TraversalRay rays[8];
    uint8_t active = 0xff;  ///< Bit i set: lane i holds a ray.

    const TraversalRay& ray(int lane) const { return rays[lane]; }
    void set(int lane, const TraversalRay& r) { rays[lane] = r; }
};

/// The closest hits of a packet's rays; lanes without a hit keep t = infinity.
struct alignas(32) HitPacket8 {
    float t[8];
    uint32_t primId[8];
    uint32_t subId[8];  ///< As Hit::subId.

    HitPacket8() {
        for (int i = 0; i < 8; ++i)
            t[i] = std::numeric_limits<float>::infinity(), primId[i] = 0, subId[i] = 0;
    }
    Hit operator[](int lane) const { return {t[lane], primId[lane], subId[lane]}; }
    void set(int lane, const Hit& h) {
        t[lane] = h.t, primId[lane] = h.primId, subId[lane] = h.subId;
    }
};

}  // namespace glint
