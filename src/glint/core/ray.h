#pragma once
/// Rays p(t) = origin + t * dir, valid for t in (tMin, tMax), and what traversal returns.

#include <cstdint>
#include <limits>

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

/// The same ray in float for traversal, with what box tests need precomputed.
struct TraversalRay {
    Vec3f origin, dir, invDir;
    float tMin, tMax;

    explicit TraversalRay(const Ray& r)
        : origin(r.origin),
          dir(r.dir),
          invDir(1 / dir.x, 1 / dir.y, 1 / dir.z),
          tMin(static_cast<float>(r.tMin)),
          tMax(static_cast<float>(r.tMax)) {}
};

/// The closest hit found by traversal, in float. The shading data is recomputed in double for
/// the winner only (Primitives::interaction).
struct Hit {
    float t = std::numeric_limits<float>::infinity();
    uint32_t primId = 0;  ///< Index into the scene's primitives.
};

/// Up to eight rays traced together (coherent camera rays), in float, one lane per ray.
struct alignas(32) RayPacket8 {
    float ox[8], oy[8], oz[8];
    float dx[8], dy[8], dz[8];
    float tMin[8], tMax[8];
    uint8_t active = 0xff;  ///< Bit i set: lane i holds a ray.

    void set(int lane, const TraversalRay& r) {
        ox[lane] = r.origin.x, oy[lane] = r.origin.y, oz[lane] = r.origin.z;
        dx[lane] = r.dir.x, dy[lane] = r.dir.y, dz[lane] = r.dir.z;
        tMin[lane] = r.tMin, tMax[lane] = r.tMax;
    }
};

/// The closest hits of a packet's rays; lanes without a hit keep t = infinity.
struct alignas(32) HitPacket8 {
    float t[8];
    uint32_t primId[8];

    HitPacket8() {
        for (int i = 0; i < 8; ++i) t[i] = std::numeric_limits<float>::infinity(), primId[i] = 0;
    }
    Hit operator[](int lane) const { return {t[lane], primId[lane]}; }
};

}  // namespace glint
